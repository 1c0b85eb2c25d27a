// The junction's nodes: coincident ones merged before the cut faces are meshed again, their gaps measured after.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "core/geometry.h"
#include "mesher/mesh_union.h"
#include "mesher/surface_mesh.h"

namespace sizemesh::cut_faces_detail {

// Boundary plus non-manifold edges: a rebuilt mesh must not have more.
size_t open_edges(const SurfaceMesh& s);

// Nodes at one point merged (a cut that meets a CAD curve makes one on each
// side of it), and the triangles that collapse with them dropped; the
// junction's edges follow. Nothing changes when a merge would open an edge.
// True when s changed.
bool merge_coincident(SurfaceMesh& s, std::vector<std::array<int, 2>>& junction, double tol);

// The junction's nodes, and each one's largest distance from the surfaces
// of the faces around it; `off` is the distance that counts as off them.
void measure_junction(const SurfaceMesh& s, const Geometry& g, MeshUnionResult& u, double off);

}  // namespace sizemesh::cut_faces_detail
