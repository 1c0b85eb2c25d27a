// Delaunay edge flips in the classified background mesh: a tessellation made
// Delaunay in a face's parameter space is far from Delaunay in space where the
// parametrisation stretches (a wing skin: chordwise u, spanwise v), and its
// obtuse triangles make the linear size map steep across their short height
// (Eq. 11), which lowers sizes far from any feature.
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "background/background_mesh.h"
#include "core/geometry.h"

namespace sizemesh {
namespace {

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
    // Each pass flips disjoint pairs; a flip makes no angle smaller than the
    // smallest of the pair, so passes end (bounded anyway). A pair is looked
    // at again only when one of its four vertices belongs to a pair flipped
    // since it was last looked at: nothing else changes its test (its
    // triangles, their neighbours, the edge a flip would make), so the flips
    // are those of looking at every pair, for a fraction of the work.
    std::vector<char> touched(patch.vertex.size(), 1), touched_now(patch.vertex.size(), 0);
    for (int pass = 0; pass < 64; ++pass) {
      std::vector<char> done(patch.tris.size(), 0);
      int n = 0;
      for (int t = 0; t < static_cast<int>(patch.tris.size()); ++t) {
        if (done[t]) continue;
        for (int k = 0; k < 3 && !done[t]; ++k) {
          const int s = patch.adj[t][k];
          if (s < 0 || done[s]) continue;
          const int c = patch.tris[t][k], a = patch.tris[t][(k + 1) % 3], b = patch.tris[t][(k + 2) % 3];
          int d = -1;
          for (int j = 0; j < 3; ++j)
            if (patch.tris[s][j] != a && patch.tris[s][j] != b) d = patch.tris[s][j];
          if (d < 0) continue;
          if (!(touched[a] || touched[b] || touched[c] || touched[d] || touched_now[a] || touched_now[b] ||
                touched_now[c] || touched_now[d]))
            continue;
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
          patch.tris[t] = {c, a, d};
          patch.tris[s] = {c, d, b};
          edge_of.erase(edge_key(ga, gb));
          edge_of.emplace(edge_key(gc, gd), -1);
          done[t] = done[s] = 1;
          touched_now[a] = touched_now[b] = touched_now[c] = touched_now[d] = 1;
          ++n;
        }
      }
      if (n == 0) break;
      touched.swap(touched_now);
      std::fill(touched_now.begin(), touched_now.end(), 0);
      flips += n;
      build_adjacency(patch);
    }
  }
  if (flips) assemble_background(bg, g, curve_edges(bg));
  return flips;
}

}  // namespace sizemesh
