// The bands along the union's cuts remeshed to the size map's size.
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

// The bands along the cuts (the triangles touching a cut node and one ring
// more) remeshed to the size map's size there: CGAL's isotropic remeshing,
// the cut curves and CAD face borders kept as constraints (their nodes slide
// along them), B-rep points and nodes where three faces meet fixed. A
// periodic face counts as two halves of its period, so its seam stays a line
// of edges (the cut faces' remesher walks the face's region in uv across it).
// One call per size class (a factor 1.25 apart), each over every band of
// that class.
void remesh_bands(Tracked& t, const SurfaceMesh& s, const Geometry& g, const std::vector<double>& node_h,
                  std::map<int, std::set<int>>& near_cut, MeshUnionResult& out);

}  // namespace sizemesh::mesh_union_detail
