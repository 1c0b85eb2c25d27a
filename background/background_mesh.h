// The classified background mesh (paper section 3.1, Definition 1).
//
// One global triangle mesh built from the B-rep tessellation: vertices are
// shared across faces, every vertex/edge/triangle is classified on the B-rep
// entity it lies on, and every face keeps its own uv triangulation (where a
// seam vertex appears twice, with its two uvs) for size queries in uv.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "cad/tessellate.h"
#include "core/mesh_topology.h"
#include "core/types.h"

namespace sizemesh {

class Geometry;
class Model;

// One face's triangulation in its own parameter space.
struct FacePatch {
  int face = 0;                             // face id
  std::vector<int> vertex;                  // #n local -> global vertex
  std::vector<Vec2> uv;                     // #n local uv
  std::vector<std::array<int, 3>> tris;     // #t local vertex ids, counter-clockwise in uv
  std::vector<std::array<int, 3>> adj;      // #t neighbour across the edge opposite corner k, -1 on the boundary
  std::vector<int> global_tri;              // #t global triangle id, -1 where degenerate in xyz (poles)
};

struct BackgroundMesh {
  // Vertices: #V
  std::vector<Vec3> xyz;
  std::vector<int8_t> dim;     // classification dimension: 0 point, 1 curve, 2 face
  std::vector<int> entity;     // id of the point, curve or face the vertex is classified on
  std::vector<double> curve_t; // curve parameter of dimension-1 vertices (NaN for the others)
  // Triangles: #T (global vertex ids, oriented as the face lies in its shell)
  std::vector<std::array<int, 3>> tris;
  std::vector<int> tri_face;   // face id per triangle
  // Edges: #E unique vertex pairs (a < b)
  std::vector<std::array<int, 2>> edges;
  std::vector<int> edge_curve; // curve id per edge, 0 for edges inside a face
  std::vector<std::array<int, 3>> tri_edges;  // #T edge ids of triangle sides (k, k+1)
  // Per face (index face id - 1)
  std::vector<FacePatch> patches;
  // Faces of positive area the tessellation gave no triangles: their patch is
  // empty and a size query there takes the nearest other face's size.
  std::vector<int> faces_without_patch;
  // Vertex -> (face, local vertex) uses, CSR: uses of v are [use_start[v], use_start[v+1])
  std::vector<int> use_start;
  std::vector<int> use_face, use_local;

  int num_vertices() const { return static_cast<int>(xyz.size()); }
  int num_triangles() const { return static_cast<int>(tris.size()); }
  double area() const;
  // Edge -> number of triangles using it (watertight closed shells: all 2).
  std::vector<int> edge_valence() const;
  // Vertex -> incident edge ids, CSR form.
  void vertex_edges(std::vector<int>& start, std::vector<int>& edge_ids) const;
  // edge_key(a, b) -> edge id, for every edge.
  std::unordered_map<uint64_t, int> edge_index() const;
};

// The classified mesh of a tessellation of g's faces (cad/tessellate.h).
BackgroundMesh build_background_mesh(const Tessellation& tess, const Geometry& g);
// The same from the model's BRepMesh tessellation.
BackgroundMesh build_background_mesh(const Model& model, const BackgroundOptions& options = {});

// Splits edges at their midpoints: an edge on a curve at the middle of its
// curve parameter range (one new vertex shared by every face using the curve,
// with its uv from each face's parameter curve), an edge inside a face at the
// middle of its uv. Every triangle touching a split edge is re-triangulated
// (one split side: 2 triangles, two: 3, three: 4), all classification is kept,
// and the global triangles, edges and uses are rebuilt. Edges of triangles
// collapsed onto a pole are left alone. Returns the number of edges split,
// which is the number of vertices added: an edge inside faces counts once per
// face holding it (two faces may each join the same two boundary vertices by
// a chord; each gets its own midpoint on its own surface).
int split_edges(BackgroundMesh& bg, const Geometry& g, const std::vector<int>& edges);

// Flips edges inside faces until every pair of triangles across one is
// Delaunay in space (the angles opposite the edge sum to at most pi, within
// a margin of about 17 degrees), where
// the flip keeps both triangles counter-clockwise in the face's uv and does
// not fold in space. Curve edges, faces with a pole and flips that would
// repeat an existing edge are left alone. Returns the number of flips.
int flip_to_delaunay(BackgroundMesh& bg, const Geometry& g);

// --- building blocks shared by the builders above ---
// Fills patch.adj from patch.tris: neighbour across the edge opposite each corner.
void build_adjacency(FacePatch& patch);
// One edge of a curve's chain of vertices.
struct CurveEdge {
  std::array<int, 2> v;
  int curve;
};
// The curve edges of bg, to re-assemble it after its patches changed.
std::vector<CurveEdge> curve_edges(const BackgroundMesh& bg);
// Rebuilds tris, tri_face, global_tri, edges (the curves' first), tri_edges and
// the vertex uses from the patches and the curves' edges.
void assemble_background(BackgroundMesh& bg, const Geometry& g, const std::vector<CurveEdge>& curve_edges);

}  // namespace sizemesh
