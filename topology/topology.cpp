#include "topology/topology.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace sizemesh {

const char* curve_kind_name(CurveKind k) {
  switch (k) {
    case CurveKind::Virtual: return "smooth";
    case CurveKind::Seam: return "seam";
    case CurveKind::Angle: return "angle";
    case CurveKind::Marker: return "marker";
    case CurveKind::User: return "user";
    case CurveKind::Boundary: return "boundary";
    case CurveKind::Degenerate: return "degenerate";
  }
  return "?";
}

int Topology::count(CurveKind k) const { return static_cast<int>(std::count(curve_kind.begin(), curve_kind.end(), k)); }

namespace {

struct Use {
  int face, side;
};

// The unit normal of face f at uv, out of its shell; zero where it has none.
Vec3 face_normal(const Geometry& g, int f, const Vec2& uv) {
  const SurfaceD1 d = g.eval_face(f, uv);
  Vec3 n = d.du.cross(d.dv);
  const double len = n.norm();
  if (!(len > 1e-300) || !std::isfinite(len)) return Vec3::Zero();
  n /= len;
  return g.face_reversed(f) ? Vec3(-n) : n;
}

// The largest angle between the two faces' normals along curve c, sampled
// at interior parameters (its ends may be poles); -1 when no sample has both.
double turn_across(const Geometry& g, int c, const Use& a, const Use& b) {
  double t0, t1;
  g.curve_range(c, t0, t1);
  double worst = -1;
  constexpr int kSamples = 7;
  for (int i = 0; i < kSamples; ++i) {
    const double t = t0 + (t1 - t0) * (0.05 + 0.9 * i / (kSamples - 1));
    const Vec3 na = face_normal(g, a.face, g.eval_pcurve(c, a.face, a.side, t));
    const Vec3 nb = face_normal(g, b.face, g.eval_pcurve(c, b.face, b.side, t));
    if (na.isZero() || nb.isZero()) continue;
    worst = std::max(worst, std::acos(std::clamp(na.dot(nb), -1.0, 1.0)) * 180 / kPi);
  }
  return worst;
}

int find(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace

Topology build_topology(const Geometry& g, const std::vector<int>& face_class, const std::set<int>& hard_curves,
                        double feature_angle_deg, bool enabled) {
  Topology t;
  t.enabled = enabled;
  t.feature_angle_deg = feature_angle_deg;
  const int nf = g.num_faces(), nc = g.num_curves(), np = g.num_points();
  std::vector<std::vector<Use>> uses(nc + 1);
  for (int f = 1; f <= nf; ++f)
    for (const FaceLoop& loop : g.face_loops(f))
      for (const CurveUse& u : loop)
        if (u.curve >= 1 && u.curve <= nc) uses[u.curve].push_back({f, u.side});
  const auto cls = [&](int f) { return f - 1 < static_cast<int>(face_class.size()) ? face_class[f - 1] : 0; };

  t.curve_kind.assign(nc, CurveKind::Boundary);
  t.curve_turn_deg.assign(nc, -1.0);
  std::vector<int> parent(nf + 1);
  std::iota(parent.begin(), parent.end(), 0);
  for (int c = 1; c <= nc; ++c) {
    auto& u = uses[c];
    CurveKind& kind = t.curve_kind[c - 1];
    if (g.curve_degenerated(c)) {
      kind = CurveKind::Degenerate;
      continue;
    }
    if (u.size() != 2) continue;  // a free edge or a non-manifold one
    if (u[0].face == u[1].face) {
      kind = CurveKind::Seam;
      continue;
    }
    const double turn = turn_across(g, c, u[0], u[1]);
    t.curve_turn_deg[c - 1] = turn;
    if (hard_curves.count(c)) kind = CurveKind::User;
    else if (cls(u[0].face) != cls(u[1].face)) kind = CurveKind::Marker;
    else if (turn < 0 || turn > feature_angle_deg) kind = CurveKind::Angle;
    else kind = CurveKind::Virtual;
    if (enabled && kind == CurveKind::Virtual) parent[find(parent, u[0].face)] = find(parent, u[1].face);
  }

  // Composite ids in the order of their first face.
  t.face_composite.assign(nf, 0);
  std::vector<int> id(nf + 1, 0);
  for (int f = 1; f <= nf; ++f) {
    const int root = find(parent, f);
    if (!id[root]) id[root] = ++t.composites;
    t.face_composite[f - 1] = id[root];
  }

  // Corners: where one feature curve ends, three or more meet, or two turn
  // by more than the feature angle.
  std::vector<std::vector<Vec3>> leaving(np + 1);
  int hard_count = 0;
  for (int c = 1; c <= nc; ++c) {
    if (!t.hard(c) || t.curve_kind[c - 1] == CurveKind::Degenerate) continue;
    ++hard_count;
    double t0, t1;
    g.curve_range(c, t0, t1);
    const int a = g.curve_start_point(c), b = g.curve_end_point(c);
    if (a >= 1 && a <= np) leaving[a].push_back(g.curve_tangent(c, t0).normalized());
    if (b >= 1 && b <= np) leaving[b].push_back(-g.curve_tangent(c, t1).normalized());
  }
  t.point_corner.assign(np, 0);
  int smooth_points = 0;
  for (int p = 1; p <= np; ++p) {
    const auto& v = leaving[p];
    if (v.empty()) continue;
    const bool through = v.size() == 2 && v[0].allFinite() && v[1].allFinite() &&
                         std::acos(std::clamp(-v[0].dot(v[1]), -1.0, 1.0)) * 180 / kPi < feature_angle_deg;
    t.point_corner[p - 1] = !through;
    smooth_points += through;
  }
  t.composite_curves = std::max(0, hard_count - smooth_points);

  // Composite curves: feature curves joined at points that are no corner.
  std::vector<int> chain(nc + 1);
  std::iota(chain.begin(), chain.end(), 0);
  std::vector<int> first_at(np + 1, 0);
  for (int c = 1; c <= nc; ++c) {
    if (!t.hard(c) || t.curve_kind[c - 1] == CurveKind::Degenerate) continue;
    for (int p : {g.curve_start_point(c), g.curve_end_point(c)}) {
      if (p < 1 || p > np || t.point_corner[p - 1]) continue;
      if (!first_at[p]) first_at[p] = c;
      else chain[find(chain, c)] = find(chain, first_at[p]);
    }
  }
  std::vector<double> total(nc + 1, 0.0);
  for (int c = 1; c <= nc; ++c) total[find(chain, c)] += g.curve_length(c);
  t.chain_length.assign(nc, 0.0);
  for (int c = 1; c <= nc; ++c) t.chain_length[c - 1] = total[find(chain, c)];
  return t;
}

}  // namespace sizemesh
