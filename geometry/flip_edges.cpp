// Delaunay edge flips in the classified background mesh: a tessellation made
// Delaunay in a face's parameter space is far from Delaunay in space where the
// parametrisation stretches (a wing skin: chordwise u, spanwise v), and its
// obtuse triangles make the linear size map steep across their short height
// (Eq. 11), which lowers sizes far from any feature.
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "geometry/background_mesh.h"
#include "geometry/geometry.h"

namespace sizemesh {
namespace {

constexpr double kPi = 3.14159265358979323846;
// How far past pi the opposite angles must sum for a flip (radians, about 17
// degrees): only clearly obtuse pairs are flipped. Pairs close to cocircular
// (the two halves of a tessellated rectangle) are left as built, and the
// background changes no more than the gradation needs.
constexpr double kFlipMargin = 0.3;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Angle at o in the triangle (o, a, b), in space.
double angle_at(const Vec3& o, const Vec3& a, const Vec3& b) {
  const Vec3 u = a - o, v = b - o;
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

// The smallest angle of the triangle (a, b, c), in space.
double smallest_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  return std::min({angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)});
}

}  // namespace

std::vector<CurveEdge> curve_edges(const BackgroundMesh& bg) {
  std::vector<CurveEdge> out;
  for (size_t e = 0; e < bg.edges.size(); ++e)
    if (bg.edge_curve[e]) out.push_back({bg.edges[e], bg.edge_curve[e]});
  return out;
}

int flip_to_delaunay(BackgroundMesh& bg, const Geometry& g) {
  // Every edge the mesh has, across all faces: a flip must not create an
  // edge that exists already (two vertices of a curve, or of another face).
  // Edges a flip makes are inside a face (id -1 here).
  std::unordered_map<uint64_t, int> edge_of = bg.edge_index();
  auto on_curve = [&](uint64_t key) {
    const auto it = edge_of.find(key);
    return it != edge_of.end() && it->second >= 0 && bg.edge_curve[it->second] != 0;
  };

  int flips = 0;
  for (FacePatch& patch : bg.patches) {
    bool degenerate = false;
    for (int gt : patch.global_tri) degenerate |= gt < 0;
    if (degenerate) continue;  // a pole's collapsed triangles: left as built
    const auto& x = bg.xyz;
    auto X = [&](int l) -> const Vec3& { return x[patch.vertex[l]]; };
    // Lawson's flips from a stack of edges: each flip puts the four edges
    // around its pair back on the stack, so a flip's effect travels as far as
    // it must within the one call (a tessellation stretched along a fuselage
    // takes waves of flips across thousands of triangles). Work is bounded:
    // in space, unlike the plane, the flips need not end by themselves.
    const int nt = static_cast<int>(patch.tris.size());
    const long long budget = 64LL * nt + 1000;
    long long looked = 0;
    std::vector<std::pair<int, int>> stack;  // (triangle, corner opposite the edge)
    stack.reserve(3 * nt);
    for (int t = nt - 1; t >= 0; --t)
      for (int k = 2; k >= 0; --k)
        if (patch.adj[t][k] > t) stack.emplace_back(t, k);
    auto slot = [&](int tri, int neighbour) {
      for (int j = 0; j < 3; ++j)
        if (patch.adj[tri][j] == neighbour) return j;
      return -1;
    };
    while (!stack.empty() && looked++ < budget) {
      const auto [t, k] = stack.back();
      stack.pop_back();
      const int s = patch.adj[t][k];
      if (s < 0) continue;
      const int c = patch.tris[t][k], a = patch.tris[t][(k + 1) % 3], b = patch.tris[t][(k + 2) % 3];
      int d = -1;
      for (int j = 0; j < 3; ++j)
        if (patch.tris[s][j] != a && patch.tris[s][j] != b) d = patch.tris[s][j];
      if (d < 0) continue;
      const int ga = patch.vertex[a], gb = patch.vertex[b], gc = patch.vertex[c], gd = patch.vertex[d];
      if (gc == gd || on_curve(edge_key(ga, gb)) || edge_of.count(edge_key(gc, gd))) continue;
      // Not Delaunay in space: the angles opposite (a, b) sum to more than pi.
      if (!(angle_at(X(c), X(a), X(b)) + angle_at(X(d), X(b), X(a)) > kPi + kFlipMargin)) continue;
      // The new pair must stay counter-clockwise in uv, with margin.
      const Vec2 &ua = patch.uv[a], &ub = patch.uv[b], &uc = patch.uv[c], &ud = patch.uv[d];
      const double quad = std::abs(cross(ua - uc, ub - uc)) + std::abs(cross(ub - ud, ua - ud));
      if (!(cross(ua - uc, ud - uc) > 1e-6 * quad && cross(ud - uc, ub - uc) > 1e-6 * quad)) continue;
      // And not fold in space against the pair it replaces.
      const Vec3 before = (X(a) - X(c)).cross(X(b) - X(c)) + (X(b) - X(d)).cross(X(a) - X(d));
      const Vec3 n1 = (X(a) - X(c)).cross(X(d) - X(c)), n2 = (X(d) - X(c)).cross(X(b) - X(c));
      if (!(n1.dot(before) > 0 && n2.dot(before) > 0)) continue;
      // And raise the pair's smallest angle: every flip then raises the
      // triangulation's sorted angles, so no flip is ever undone and the
      // flips end (on a bent quad both diagonals can pass the test above).
      const double was = std::min(smallest_angle(X(c), X(a), X(b)), smallest_angle(X(d), X(b), X(a)));
      if (!(std::min(smallest_angle(X(c), X(a), X(d)), smallest_angle(X(c), X(d), X(b))) > was * (1 + 1e-9))) continue;
      // Neighbours across (b, c), (c, a) of t and (a, d), (d, b) of s.
      const int n_bc = patch.adj[t][(k + 1) % 3], n_ca = patch.adj[t][(k + 2) % 3];
      int n_ad = -1, n_db = -1;
      for (int j = 0; j < 3; ++j) {
        if (patch.tris[s][j] == b) n_ad = patch.adj[s][j];
        if (patch.tris[s][j] == a) n_db = patch.adj[s][j];
      }
      // A pair that shares two edges (a fold of the tessellation) stays.
      if (n_bc == s || n_ca == s || n_ad == t || n_db == t) continue;
      patch.tris[t] = {c, a, d};
      patch.tris[s] = {c, d, b};
      patch.adj[t] = {n_ad, s, n_ca};  // opposite c, a, d
      patch.adj[s] = {n_db, n_bc, t};  // opposite c, d, b
      if (n_ad >= 0) {
        const int j = slot(n_ad, s);
        if (j >= 0) patch.adj[n_ad][j] = t;
      }
      if (n_bc >= 0) {
        const int j = slot(n_bc, t);
        if (j >= 0) patch.adj[n_bc][j] = s;
      }
      edge_of.erase(edge_key(ga, gb));
      edge_of.emplace(edge_key(gc, gd), -1);
      ++flips;
      for (const auto& e : {std::make_pair(t, 0), std::make_pair(t, 2), std::make_pair(s, 0), std::make_pair(s, 1)})
        stack.push_back(e);
    }
  }
  if (flips) assemble_background(bg, g, curve_edges(bg));
  return flips;
}

}  // namespace sizemesh
