// Advancing-front triangulation of one face in its uv domain under the metric
// M = J^T J / h^2 (paper 4.1), with Tremel's two robustness procedures used
// adaptively: the ideal point is placed in uv and, only when that gives a poor
// triangle, placed in space and projected onto the surface; every triangle is
// also checked in space (normal agrees with the surface, shape).
//
// One step: take the shortest front edge (metric length = chord / h); place
// the ideal point equilateral in the metric at the edge's midpoint (side s = 1,
// bounded by the edge's own length); candidates are the front nodes within a
// metric ball around it (found through an EdgeGrid) and the ideal point itself,
// ranked by metric distance; accept the first triangle that is counter-
// clockwise in uv, crosses no front edge, holds no front node, repeats no edge
// in space (seams), faces the surface normal at its corners and centroid, and
// has a good shape in space. An edge with no acceptable triangle is tried again
// later with looser limits; a pole segment gets its ring of triangles first.
//
// Input:  fm with boundary nodes and loops (face_boundary()), fs its sampler.
// Output: fm.tris (counter-clockwise in uv) and the nodes created inside the
//         face; FrontResult says whether the front closed and, if not, why.
// Terminates on every input: at most max_steps tries at front edges (a
// successful step adds one triangle), then the front stops and reports it.
// Retrying a failed face with a later strategy (from the same boundary) is the caller's choice.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "mesher/face_mesh.h"

namespace sizemesh {

struct FrontResult {
  bool ok = false;
  std::string reason;
  int fronts_3d = 0;  // ideal points computed in space (Tremel procedure 1)
  std::vector<std::array<int, 2>> open_edges;  // front left when it failed
  long long steps = 0;                          // tries at front edges
  long long work = 0;                           // front edges and nodes looked at (its work budget's measure)
};

// Strategies 0 .. kStrategyCount-1, from the best shapes to the most robust.
// A lenient run lets the loosest levels of strategies 2 and 3 accept a
// triangle turned against the surface at its centroid (never otherwise).
constexpr int kStrategyCount = 4;
FrontResult advancing_front(FaceMesh& fm, FaceSurface& fs, int strategy, long long max_steps, bool lenient);

// The step budget of a face: a few times the triangles its size map asks for
// (sizing/triangle_estimate.h), plus room for the boundary and a constant.
long long front_step_budget(double expected_triangles, int boundary_nodes);

}  // namespace sizemesh
