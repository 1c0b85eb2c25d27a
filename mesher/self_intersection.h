// Self-intersection check of a surface mesh: pairs of triangles that meet
// anywhere but at the nodes they share (paper 4.1 asks for a valid mesh; a
// volume mesher refuses one that crosses itself).
//
// Input:  m, the mesh (only xyz and tris are read)
// Output: the number of intersecting pairs, and the first `keep` of them
//         (triangle ids, lower first) for the report.
// Rules by shared nodes: none, the triangles meet; one node v, the edge
// opposite v of either meets the other; an edge, they are coplanar and fold
// onto the same side; all three, a duplicate. Candidates come from box overlaps
// in the triangle hierarchy; the tests are floating point (core/predicates.h).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "mesher/surface_mesh.h"

namespace sizemesh {

struct SelfIntersections {
  long long pairs = 0;
  std::vector<std::array<int, 2>> kept;
};

// among (optional): per triangle, 1 for those to check; only pairs holding
// one of them are tested (a local change checked without the whole mesh).
SelfIntersections find_self_intersections(const SurfaceMesh& m, size_t keep, const std::vector<char>* among = nullptr);

}  // namespace sizemesh
