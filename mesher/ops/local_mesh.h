// What the local mesh operations (mesher/ops/) share about one face's mesh:
// the shape of a triangle in space with its validity, the triangles across
// each edge, the triangles around each node (a ball) and their measure with
// the node moved, and the move of a node itself.
//
// Inputs: a FaceMesh (uv, surface samples, triangles) and its FaceSurface.
// Outputs: measures and adjacency; only apply_move() changes the mesh.
#pragma once

#include <array>
#include <vector>

#include "mesher/face_mesh.h"

namespace sizemesh::ops {

// Shape in space of (a, b, c) at the given corner samples; -1 when the triangle
// is folded in uv or turned away from the surface at a corner or at its uv
// centroid (the quality report's test for an inverted triangle).
double shape(const Vec2& ua, const Vec2& ub, const Vec2& uc, const SurfaceSample& sa, const SurfaceSample& sb,
             const SurfaceSample& sc, const FaceSurface& fs);
double shape(const FaceMesh& fm, const FaceSurface& fs, const std::array<int, 3>& t);

// Smallest angle of triangle t where its nodes lie in the assembled mesh
// (boundary nodes at their curve's xyz), in degrees.
double final_min_angle(const FaceMesh& fm, const std::array<int, 3>& t);

// Triangle neighbours: nbr[t][k] is the triangle across edge (t[k], t[k+1]), -1 on the boundary.
std::vector<std::array<int, 3>> neighbours(const FaceMesh& fm);

// In triangle t's neighbours (t < 0: none), `from` becomes `to`.
void repoint(std::vector<std::array<int, 3>>& nbr, int t, int from, int to);

// Where triangle T2 holds edge a -> b of its neighbour reversed: the j with
// T2[j] == b and T2[j + 1] == a (its third corner is T2[j + 2]); -1 if none.
int reversed_edge(const std::array<int, 3>& T2, int a, int b);

// Triangles around every node: those of node i are tri_of[start[i] .. start[i+1]).
struct Balls {
  std::vector<int> start, tri_of;
  explicit Balls(const FaceMesh& fm);
};

// Node i's triangles with i moved to (uv, s): whether they all stay valid,
// their worst shape, their smallest corner angle (degrees) and how many are
// under 12 degrees (pole triangles only need to stay counter-clockwise).
// `lenient`, per triangle of the ball: it already failed the shape's validity
// (the surface's normal turns more than 60 degrees within it) and need only
// stay counter-clockwise in uv and not turned against the surface at its
// centroid, the report's inverted test.
struct BallMeasure {
  bool valid = true;
  double shape = 2, angle = 180;
  int thin = 0;
  // Fewer thin triangles first, then a larger smallest angle.
  bool better_than(const BallMeasure& o, double by) const {
    return thin < o.thin || (thin == o.thin && angle > o.angle + by);
  }
};

BallMeasure measure_ball(const FaceMesh& fm, const FaceSurface& fs, const Balls& b, int i, const Vec2& uv,
                         const SurfaceSample& s, const std::vector<char>* lenient = nullptr);

// Whether node i's triangles with i moved to (uv, s) all stay valid with a
// shape of at least `worst`: measure_ball's valid and shape >= worst, without
// its angles, and stopping at the first triangle that fails.
bool ball_keeps_shape(const FaceMesh& fm, const FaceSurface& fs, const Balls& b, int i, const Vec2& uv,
                      const SurfaceSample& s, double worst);

// A node's new place (uv and the surface sample there), the decision of a
// check that moves a node (check_smooth, check_rescue); ok false: it stays.
struct NodeMove {
  bool ok = false;
  Vec2 uv;
  SurfaceSample s;
};

// Node i moved as m says (m.ok).
void apply_move(FaceMesh& fm, int i, const NodeMove& m);

}  // namespace sizemesh::ops
