// The surface mesher (paper 4.1), top level:
//   1. discretise every curve once into a unit mesh (paper 2.1, Eq. 1a-1b),
//      shared by every face that uses it          (discretise_curves.h)
//   2. per face, in parallel (TBB), independent of the others:
//      a. initial front: boundary loops in uv       (face_boundary.h)
//      b. advancing front under M = J^T J / h^2, Tremel's procedures adaptively;
//         a face whose front gets stuck is meshed again with a more robust
//         strategy                                    (advancing_front.h)
//      c. swaps and smoothing                         (optimise.h)
//   3. assemble in face order: nodes on B-rep points and curves shared by index,
//      triangles flipped where the face is reversed in its shell; a pair of
//      triangles on the same nodes facing apart (two faces back to back, no
//      thickness between them) dropped.
//
// Inputs:
//   g   the B-rep (thread-safe)
//   h   the size function (thread-safe)
//   o   thread count and optimisation passes
// Output: SurfaceMesh (mesher/surface_mesh.h). A face that cannot be meshed is
// listed in failures and left out; the rest is kept. The mesh does not depend
// on the thread count.
#pragma once

#include <string>

#include "core/geometry.h"
#include "mesher/face_mesh.h"
#include "mesher/surface_mesh.h"
#include "core/size_field.h"

namespace sizemesh {

SurfaceMesh mesh_surface(const Geometry& g, const SizeField& h, const MeshOptions& o = {});

// The inside of face fm.face meshed from the boundary fm holds (nodes with
// uv in the surface's parameters, a global id and shared_xyz each; loops with
// the face on their left in uv): the front, its strategies and the optimiser
// of mesh_surface(). On success fm holds the mesh (uv the surface's, new
// inner nodes with global id -1); else false and `reason`.
bool mesh_within(const Geometry& g, const SizeField& h, FaceMesh& fm, const MeshOptions& o, std::string& reason);

// Two faces that lie back to back over a strip (a fin or a tip whose two
// sides meet with no thickness between them) mesh that strip twice: a pair
// of triangles on the same three nodes, facing away from each other. The
// pair bounds no volume and its edges are used four times, so no solid's
// surface can hold it: both go (counted in m.stats.back_to_back_dropped).
// Triangles that do not pair stay; node ids do not change.
void drop_back_to_back(SurfaceMesh& m);

// Two faces that meet along two curves close together (a strut's sides at a
// thin tip) may each mesh the same inner edge between the same two curve
// nodes: an edge used four times. The edge is flipped inside one face (its
// two triangles' quad takes the other diagonal) where the flip keeps their
// orientation (counted in m.stats.shared_edges_flipped).
void flip_shared_inner_edges(SurfaceMesh& m);

}  // namespace sizemesh
