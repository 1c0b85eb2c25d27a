#include "sizing/refine_background.h"

#include <algorithm>
#include <cmath>

#include "core/triangle_bvh.h"
#include "sizing/curvature_size.h"
#include "sizing/initial_sizes.h"
#include "sizing/smooth.h"
#include "sizing/sources.h"
#include "sizing/triangle_estimate.h"

namespace sizemesh {
namespace {

// What the curvature would allow at the middle of edge (a, b): the smallest
// curvature size over the faces holding both ends, at the uv midpoint there,
// and what the size sources ask there (a source smaller than the triangles
// around it is found the same way as a curvature peak they step over).
// A split where this is no larger than the ends' sizes would add a vertex
// that only repeats them (a leading edge at h_min, all along).
double midpoint_curvature_size(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p, double h_max,
                               int a, int b, CurvatureMemo& memo) {
  double h = source_size(p.sources, 0.5 * (bg.xyz[a] + bg.xyz[b]), h_max, std::log(p.beta));
  for (int ua = bg.use_start[a]; ua < bg.use_start[a + 1]; ++ua)
    for (int ub = bg.use_start[b]; ub < bg.use_start[b + 1]; ++ub) {
      const int f = bg.use_face[ua];
      if (bg.use_face[ub] != f) continue;
      const FacePatch& patch = bg.patches[f - 1];
      const Vec2 mid = 0.5 * (patch.uv[bg.use_local[ua]] + patch.uv[bg.use_local[ub]]);
      h = std::min(h, memo.face(g, f, mid, p));
    }
  return h;
}

// The longest side of background triangle t (an edge id).
int longest_edge(const BackgroundMesh& bg, int t) {
  const auto& tr = bg.tris[t];
  auto length = [&](int k) { return (bg.xyz[tr[k]] - bg.xyz[tr[(k + 1) % 3]]).norm(); };
  int longest = 0;
  for (int k = 1; k < 3; ++k)
    if (length(k) > length(longest)) longest = k;
  return bg.tri_edges[t][longest];
}

}  // namespace

void refine_background(const Geometry& g, BackgroundMesh& bg, const SizingParams& p, double diagonal, SizeMap& m,
                       RefineStats* stats, bool flips) {
  RefineStats s;
  CurvatureMemo memo;
  s.vertices_before = bg.num_vertices();
  // Delaunay in space first: the tessellation's obtuse triangles would make
  // Eq. 11 lower sizes across their short height (see flip_to_delaunay).
  if (p.refine_background && flips) {
    s.flips = flip_to_delaunay(bg, g);
    if (s.flips > 0) m = initial_sizes(g, bg, p, diagonal, &memo);
  }
  for (int round = 0; round < kRefineMaxRounds && p.refine_background; ++round) {
    std::vector<double> h = m.h_initial;
    smooth_edges(bg, m.edge_log_beta, h);  // Eq. 12: what gradation leaves at the vertices
    // A map already asking for more triangles than the budget will be refused:
    // refining it further is work for nothing.
    if (estimate_triangles(bg, h, {}, g.num_faces()).total > p.max_triangles) break;
    std::vector<int> split;
    for (int e = 0; e < static_cast<int>(bg.edges.size()); ++e) {
      const auto [a, b] = bg.edges[e];
      const double l = (bg.xyz[a] - bg.xyz[b]).norm();
      const double lo = std::min(h[a], h[b]), hi = std::max(h[a], h[b]);
      const double linear = 0.5 * (lo + hi);
      const double cap = std::max(m.h_cap[a], m.h_cap[b]);
      // Graded against linear at the middle, and a quarter of the way from the
      // smaller end: with the far end at h_max the middle can never gain 2x.
      double gain = 0;
      for (double x : {0.25, 0.5})
        gain = std::max(gain, std::min(cap, lo + m.edge_log_beta[e] * x * l) / (lo + x * (hi - lo)));
      if (!(gain > kRefineGain) && !(m.h_min * kCurvatureMiss < linear)) continue;
      const double curved = midpoint_curvature_size(g, bg, p, m.h_max, a, b, memo);
      // Room to grow that the curvature there allows, or a curvature the ends miss.
      if ((gain > kRefineGain && curved > kRefineGain * linear) || std::max(curved, m.h_min) * kCurvatureMiss < linear)
        split.push_back(e);
    }
    // A curvature peak (or a size source) inside a triangle: its longest edge is split.
    for (const FacePatch& patch : bg.patches)
      for (size_t t = 0; t < patch.tris.size(); ++t) {
        const int gt = patch.global_tri[t];
        if (gt < 0) continue;
        const auto& lt = patch.tris[t];
        const double hv[3] = {h[patch.vertex[lt[0]]], h[patch.vertex[lt[1]]], h[patch.vertex[lt[2]]]};
        if (!(m.h_min * kCurvatureMiss < std::max({hv[0], hv[1], hv[2]}))) continue;
        // The centroid and the three points halfway from it to the corners.
        bool missed = false;
        static const Vec3 kSamples[4] = {Vec3(2, 2, 2) / 6, Vec3(4, 1, 1) / 6, Vec3(1, 4, 1) / 6, Vec3(1, 1, 4) / 6};
        for (const Vec3& w : kSamples) {
          const Vec2 c = w[0] * patch.uv[lt[0]] + w[1] * patch.uv[lt[1]] + w[2] * patch.uv[lt[2]];
          const double linear = w[0] * hv[0] + w[1] * hv[1] + w[2] * hv[2];
          double wanted = memo.face(g, patch.face, c, p);
          if (!p.sources.empty()) {
            const Vec3 x = w[0] * bg.xyz[patch.vertex[lt[0]]] + w[1] * bg.xyz[patch.vertex[lt[1]]] +
                           w[2] * bg.xyz[patch.vertex[lt[2]]];
            wanted = std::min(wanted, source_size(p.sources, x, m.h_max, std::log(p.beta)));
          }
          missed |= std::max(wanted, m.h_min) * kCurvatureMiss < linear;
          if (missed) break;
        }
        // A source smaller than the triangle may lie between those samples:
        // also the triangle's point closest to each source's centre.
        for (size_t k = 0; k < p.sources.size() && !missed; ++k) {
          const Vec3& A = bg.xyz[patch.vertex[lt[0]]];
          const Vec3& B = bg.xyz[patch.vertex[lt[1]]];
          const Vec3& C = bg.xyz[patch.vertex[lt[2]]];
          const SizeSource& src = p.sources[k];
          const Vec3 centre = src.kind == SizeSource::Kind::Point || src.kind == SizeSource::Kind::Sphere
                                  ? src.a
                                  : Vec3(0.5 * (src.a + src.b));
          const Vec3 w = TriangleBVH::closest_barycentric(centre, A, B, C);
          const double linear = w[0] * hv[0] + w[1] * hv[1] + w[2] * hv[2];
          const double wanted = src.size_at(w[0] * A + w[1] * B + w[2] * C, m.h_max, std::log(p.beta));
          missed = std::max(wanted, m.h_min) * kCurvatureMiss < linear;
        }
        if (!missed) continue;
        split.push_back(longest_edge(bg, gt));
      }
    // A triangle too flat to carry the edge-graded sizes: with one corner
    // close to the opposite (long) edge, the linear interpolant's gradient
    // (Eq. 11) is the size difference over that short height, and the
    // triangle stage would lower the far corners to the near one's size,
    // and from them the whole face. Its longest edge is split, so that the
    // sizes can grade along it.
    for (int t = 0; t < bg.num_triangles(); ++t) {
      const auto& tr = bg.tris[t];
      const double lo = std::min({h[tr[0]], h[tr[1]], h[tr[2]]}), hi = std::max({h[tr[0]], h[tr[1]], h[tr[2]]});
      if (hi > kRefineGain * lo && triangle_gradient(bg, h, t) > kRefineGain * m.tri_log_beta[t])
        split.push_back(longest_edge(bg, t));
    }
    const int n = split.empty() ? 0 : split_edges(bg, g, split);
    if (n == 0) break;
    if (flips) s.flips += flip_to_delaunay(bg, g);  // the split's new triangles too
    s.rounds = round + 1;
    s.edges_split += n;
    m = initial_sizes(g, bg, p, diagonal, &memo);
  }
  s.vertices_after = bg.num_vertices();
  if (stats) *stats = s;
}

SizeMap refine_background(const Geometry& g, BackgroundMesh& bg, const SizingParams& p, double diagonal,
                          RefineStats* stats, bool flips) {
  SizeMap m = initial_sizes(g, bg, p, diagonal);
  refine_background(g, bg, p, diagonal, m, stats, flips);
  return m;
}

}  // namespace sizemesh
