// The united CGAL mesh back into a SurfaceMesh, its new and moved nodes on their CAD faces.
//
// Internal to the mesh-level union (mesher/mesh_union.cpp).
#pragma once

#include <map>
#include <set>
#include <vector>

#include "core/geometry.h"
#include "mesher/mesh_union.h"
#include "mesher/tracked_mesh.h"

namespace sizemesh::mesh_union_detail {

// s rewritten as the united mesh `base` (after the corefinements and the band
// remesh): every node the cut or the remesh made or moved put on its CAD
// faces (snap()), but for triangles moved off their surfaces to close a slot
// (their source nodes in `gap_moved`); source nodes keep their ids, new ones
// follow; the triangles `aside` (of s, kept out of the union) are added as
// they are. near_cut: per CAD face, the source triangles near a cut (uv
// hints). Fills out's junction, junction node counts and crossing pairs.
void to_surface_mesh(SurfaceMesh& s, const Geometry& g, Tracked& base, const std::set<int>& gap_moved,
                     std::map<int, std::set<int>>& near_cut, const std::vector<int>& aside, MeshUnionResult& out);

}  // namespace sizemesh::mesh_union_detail
