// Mesh-level union: the last route of a component the B-rep union could not
// take. Its closed mesh and the closed wetted surface meshed so far are cut
// where they cross (exact corefinement, CGAL's Polygon Mesh Processing) and
// only the outer parts are kept. The junction's new nodes are put on the
// exact intersection of the two CAD surfaces, and the band of triangles the
// cut crossed is remeshed to the size map's local size, so the cut leaves no
// sliver.
//
// Input:  mesh   the surface mesh of every face (mesh_surface())
//         g      its geometry (projection of the new nodes onto the faces)
//         h      the size map (the band's target size)
//         parts  per component to unite, the ids of its faces
// Output: mesh rewritten as the union; per part, why it could not be united
//         (empty when it was). The rest of the mesh keeps its nodes, their
//         classification and the triangles outside the band.
// Work:   the corefinement is linear in the triangles near the cut (box
//         filter first); the band remesh and projection in the band's size.
#pragma once

#include <array>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry.h"
#include "mesher/surface_mesh.h"
#include "core/size_field.h"

namespace sizemesh {

struct MeshUnionResult {
  std::vector<std::string> failures;  // per part: empty when united, else why not
  int united = 0;                     // parts united
  int rest_pieces_apart = 0;          // closed pieces of the rest that could not take part (their mesh intersects itself)
  int junction_nodes = 0;             // nodes on the cut curves, on both CAD surfaces
  int gap_nodes_closed = 0;           // nodes moved across a slot too thin for the mesh into the other side
  int band_triangles = 0;             // triangles of the remeshed bands
  int band_classes_undone = 0;        // size classes whose band remesh was undone (it made the surface cross itself)
  int junction_nodes_off = 0;         // of those, nodes left on the meshes (surfaces meeting at a grazing angle)
  int junction_nodes_unprojected = 0; // of those, nodes a surface's projection did not reach (left out of the gap)
  double max_junction_gap = 0;        // largest distance of a projected junction node from either surface
  std::vector<std::array<int, 2>> junction;  // the cut edges (node pairs) in the united mesh
  std::set<int> band_faces;                  // CAD faces with triangles in, or next to, a remeshed band
  long long crossing_pairs = -1;             // intersecting triangle pairs of the united mesh (-1: not counted)
};

// Counts junction node x into u: projected onto the surface of each face of
// `on` (face, uv to start from), its largest distance from them goes into
// max_junction_gap; a node some projection does not reach is unprojected;
// either, or a distance over `off`, counts it as off the surfaces.
void count_junction_node(MeshUnionResult& u, const Geometry& g, const Vec3& x,
                         std::vector<std::pair<int, Vec2>> on, double off);

MeshUnionResult unite_meshes(SurfaceMesh& mesh, const Geometry& g, const SizeField& h,
                             const std::vector<std::vector<int>>& parts);

}  // namespace sizemesh
