#include "sizing/refine_background.h"

#include <algorithm>

#include "sizing/curvature_size.h"
#include "sizing/initial_sizes.h"
#include "sizing/smooth.h"

namespace sizemesh {
namespace {

// What the curvature would allow at the middle of edge (a, b): the smallest
// curvature size over the faces holding both ends, at the uv midpoint there.
// A split where this is no larger than the ends' sizes would add a vertex
// that only repeats them (a leading edge at h_min, all along).
double midpoint_curvature_size(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p, int a, int b) {
  double h = kNoLimit;
  for (int ua = bg.use_start[a]; ua < bg.use_start[a + 1]; ++ua)
    for (int ub = bg.use_start[b]; ub < bg.use_start[b + 1]; ++ub) {
      const int f = bg.use_face[ua];
      if (bg.use_face[ub] != f) continue;
      const FacePatch& patch = bg.patches[f - 1];
      const Vec2 mid = 0.5 * (patch.uv[bg.use_local[ua]] + patch.uv[bg.use_local[ub]]);
      h = std::min(h, face_curvature_size(g, f, mid, p));
    }
  return h;
}

}  // namespace

SizeMap refine_background(const Geometry& g, BackgroundMesh& bg, const SizingParams& p, double diagonal,
                          RefineStats* stats) {
  RefineStats s;
  s.vertices_before = bg.num_vertices();
  SizeMap m = initial_sizes(g, bg, p, diagonal);
  for (int round = 0; round < kRefineMaxRounds && p.refine_background; ++round) {
    std::vector<double> h = m.h_initial;
    smooth_edges(bg, m.edge_log_beta, h);  // Eq. 12: what gradation leaves at the vertices
    std::vector<int> split;
    for (int e = 0; e < static_cast<int>(bg.edges.size()); ++e) {
      const auto [a, b] = bg.edges[e];
      const double l = (bg.xyz[a] - bg.xyz[b]).norm();
      const double linear = 0.5 * (h[a] + h[b]);
      const double graded = std::min(m.h_max, std::min(h[a], h[b]) + m.edge_log_beta[e] * 0.5 * l);
      if (graded > kRefineGain * linear && midpoint_curvature_size(g, bg, p, a, b) > kRefineGain * linear)
        split.push_back(e);
    }
    const int n = split.empty() ? 0 : split_edges(bg, g, split);
    if (n == 0) break;
    s.rounds = round + 1;
    s.edges_split += n;
    m = initial_sizes(g, bg, p, diagonal);
  }
  s.vertices_after = bg.num_vertices();
  if (stats) *stats = s;
  return m;
}

}  // namespace sizemesh
