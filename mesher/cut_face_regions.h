// A cut face's regions walked from its triangles, as boundary loops the face mesher takes (face_regions).
#pragma once

#include <cstdint>
#include <set>
#include <unordered_map>
#include <vector>

#include "core/geometry.h"
#include "mesher/face_mesh.h"
#include "mesher/junction_chains.h"
#include "mesher/surface_mesh.h"

namespace sizemesh::cut_faces_detail {

// Two region boundaries alike: the same nodes (uv, shared node, place) in the same loops.
bool same_boundary(const FaceMesh& a, const FaceMesh& b);

// The face's triangles `tris` (of `all` its triangles, the others held)
// meet at a node two or more times around it: the triangles of `all` at
// such nodes are held too, so that the rest of the face has boundary loops
// the face mesher can walk. False when there is no such node.
bool held_pinches(const SurfaceMesh& s, const std::vector<int>& all, const std::vector<int>& tris, std::set<int>& held);

// A face's regions as the face mesher takes them: boundary loops (face on
// the left in uv) with the substituted chains' new nodes in place of their
// old ones. Empty when a region's boundary cannot be walked (a pole, a
// pinched corner) or holds no single outer loop.
struct Region {
  FaceMesh boundary;
  bool flip = false;  // the face's triangles run clockwise in uv
};
std::vector<Region> face_regions(const SurfaceMesh& s, const Geometry& g, int f, const std::vector<int>& tris,
                                 const std::vector<Chain>& chains, const std::vector<int>& chain_of_edge_owner,
                                 const std::unordered_map<uint64_t, int>& chain_of_edge, bool& ok);

}  // namespace sizemesh::cut_faces_detail
