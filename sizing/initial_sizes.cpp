#include "sizing/initial_sizes.h"

#include <algorithm>
#include <cmath>

#include "core/stopwatch.h"
#include "sizing/curvature_size.h"
#include "sizing/proximity_size.h"
#include "sizing/sources.h"
#include "sizing/user_size.h"

namespace sizemesh {

namespace {


double face_beta(const SizingParams& p, int face) {
  auto it = p.face_beta.find(face);
  return it == p.face_beta.end() ? p.beta : it->second;
}

// Chordwise spacing on the wing's leading and trailing edges (their curves
// and end points): the spacing share times the chord there. On a blunt
// trailing edge's base (its faces, creases and corners): the base's width
// there over te_cells. On a wing tip's cap: tip_spacing times the tip's chord.
std::vector<double> aero_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p) {
  std::vector<double> h(bg.num_vertices(), kNoLimit);
  if (!(p.le_spacing > 0) && !(p.te_spacing > 0) && !(p.te_cells > 0) && !(p.tip_spacing > 0)) return h;
  const WingFeatures& w = p.wing;
  auto apply = [&](const std::vector<int>& curves, const std::vector<int>& composite, double share, bool leading) {
    if (!(share > 0)) return;
    for (size_t i = 0; i < curves.size(); ++i) {
      const int c = curves[i];
      auto size_at = [&](int v) {
        const double chord = w.chord_at(bg.xyz[v], composite[i], leading);
        if (chord > 0) h[v] = std::min(h[v], share * chord);
      };
      for (int v = 0; v < bg.num_vertices(); ++v)
        if (bg.dim[v] == 1 && bg.entity[v] == c) size_at(v);
      for (int pt : {g.curve_start_point(c), g.curve_end_point(c)})
        if (pt > 0 && pt <= bg.num_vertices()) size_at(pt - 1);
    }
  };
  apply(w.leading, w.leading_curve_composite, p.le_spacing, true);
  apply(w.trailing, w.trailing_curve_composite, p.te_spacing, false);
  // Vertices on the faces (sorted ids), their curves and points.
  auto on_faces = [&](const std::vector<int>& faces, const auto& size_at) {
    for (int v = 0; v < bg.num_vertices(); ++v)
      for (int u = bg.use_start[v]; u < bg.use_start[v + 1]; ++u)
        if (std::binary_search(faces.begin(), faces.end(), bg.use_face[u])) {
          const double s = size_at(v);
          if (s > 0) h[v] = std::min(h[v], s);
          break;
        }
  };
  if (p.te_cells > 0)
    for (size_t b = 0; b < w.bases.size(); ++b)
      on_faces(w.bases[b].faces, [&](int v) { return w.base_width_at(bg.xyz[v], static_cast<int>(b)) / p.te_cells; });
  if (p.tip_spacing > 0)
    for (const WingFeatures::Tip& tip : w.tips) on_faces(tip.faces, [&](int) { return p.tip_spacing * tip.chord; });
  return h;
}

// ln(beta) per triangle (its face's beta) and per edge (smallest over the faces it touches).
void gradation_bounds(const BackgroundMesh& bg, const SizingParams& p, SizeMap& m) {
  m.tri_log_beta.resize(bg.num_triangles());
  for (int t = 0; t < bg.num_triangles(); ++t) m.tri_log_beta[t] = std::log(face_beta(p, bg.tri_face[t]));
  m.edge_log_beta.assign(bg.edges.size(), std::log(p.beta));
  std::vector<bool> seen(bg.edges.size(), false);
  for (int t = 0; t < bg.num_triangles(); ++t)
    for (int e : bg.tri_edges[t]) {
      m.edge_log_beta[e] = seen[e] ? std::min(m.edge_log_beta[e], m.tri_log_beta[t]) : m.tri_log_beta[t];
      seen[e] = true;
    }
  for (int t = 0; t < bg.num_triangles(); ++t)
    if (p.edge_graded_faces.count(bg.tri_face[t])) m.tri_log_beta[t] = kNoLimit;
}

// The largest size at each vertex: h_max, or the least of its faces' own.
std::vector<double> size_caps(const BackgroundMesh& bg, const SizingParams& p, double h_max) {
  std::vector<double> cap(bg.num_vertices(), h_max);
  if (p.face_h_max.empty()) return cap;
  for (int v = 0; v < bg.num_vertices(); ++v) {
    double c = INFINITY;
    for (int u = bg.use_start[v]; u < bg.use_start[v + 1]; ++u) {
      auto it = p.face_h_max.find(bg.use_face[u]);
      c = std::min(c, it == p.face_h_max.end() ? h_max : it->second);
    }
    if (std::isfinite(c)) cap[v] = c;
  }
  return cap;
}

}  // namespace

SizeMap initial_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p, double diagonal,
                      CurvatureMemo* memo) {
  validate(p, diagonal, g.num_points(), g.num_curves(), g.num_faces());
  SizeMap m;
  m.h_min = p.resolved_h_min(diagonal);
  m.h_max = p.resolved_h_max(diagonal);
  Stopwatch clock;
  m.h_curvature = curvature_sizes(g, bg, p, memo);
  m.t_curvature = clock.lap();
  std::vector<double> h_face(bg.num_vertices(), kNoLimit), h_curve(bg.num_vertices(), kNoLimit);
  if (p.proximity) {
    h_face = face_proximity_sizes(g, bg, p);
    h_curve = curve_length_sizes(g, bg, p);
  }
  m.t_proximity = clock.lap();
  GapSizes h_gap(bg.num_vertices());
  if (p.proximity && p.local_proximity) {
    double mu_max = p.mu_d;
    for (const auto& [f, mu] : p.face_mu_d) mu_max = std::max(mu_max, mu);
    // Faces closer than the sewing tolerance (1e-5 of the diagonal) touch.
    h_gap = gap_sizes(g, bg, p, m.h_max * mu_max, 1e-5 * diagonal);
  }
  m.t_gap = clock.lap();
  m.h_user = user_sizes(g, bg, p);
  m.h_source = source_sizes(p.sources, bg.xyz, m.h_max, std::log(p.beta));
  m.h_aero = aero_sizes(g, bg, p);
  m.t_user = clock.lap();

  const int nv = bg.num_vertices();
  m.h_cap = size_caps(bg, p, m.h_max);
  const std::vector<double>& cap = m.h_cap;
  m.h_proximity.resize(nv);
  m.h_initial.resize(nv);
  m.limit.resize(nv);
  for (int v = 0; v < nv; ++v) {
    m.h_proximity[v] = std::min({h_face[v], h_curve[v], h_gap.fluid[v], h_gap.solid[v]});
    // h_a = max(h_min, min(h_d, h_c, h_u, h_s, h_max)), remembering which term won.
    std::pair<double, Limit> best{cap[v], cap[v] == m.h_max ? Limit::HMax : Limit::FarField};
    for (auto c : {std::make_pair(m.h_curvature[v], Limit::Curvature), std::make_pair(h_face[v], Limit::FaceProximity),
                   std::make_pair(h_curve[v], Limit::CurveLength), std::make_pair(h_gap.fluid[v], Limit::Gap),
                   std::make_pair(h_gap.solid[v], Limit::Thickness),
                   std::make_pair(m.h_user[v], Limit::User), std::make_pair(m.h_source[v], Limit::Source)})
      if (c.first < best.first) best = c;
    if (best.first < m.h_min) best = {m.h_min, Limit::HMin};
    // The chordwise spacing asked at a leading or trailing edge holds even
    // under h_min: it is the user's word for that curve.
    if (m.h_aero[v] < best.first) best = {m.h_aero[v], Limit::Aero};
    m.h_initial[v] = best.first;
    m.limit[v] = best.second;
  }
  m.h = m.h_initial;
  gradation_bounds(bg, p, m);
  return m;
}

}  // namespace sizemesh
