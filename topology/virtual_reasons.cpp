#include "topology/virtual_reasons.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/predicates.h"

namespace sizemesh {

namespace {

struct Use {
  int face, side;
};

}  // namespace

VirtualReasons classify_virtual_curves(const Geometry& g, const Topology& t,
                                       const std::function<double(int, const Vec2&)>& size) {
  VirtualReasons r;
  if (!t.enabled) return r;
  const int nf = g.num_faces(), nc = std::min<int>(g.num_curves(), static_cast<int>(t.curve_kind.size()));
  std::vector<std::vector<Use>> uses(nc + 1);
  std::vector<std::vector<int>> curves_of(nf + 1);
  for (int f = 1; f <= nf; ++f)
    for (const FaceLoop& loop : g.face_loops(f))
      for (const CurveUse& u : loop)
        if (u.curve >= 1 && u.curve <= nc) uses[u.curve].push_back({f, u.side}), curves_of[f].push_back(u.curve);
  std::vector<double> width(nf + 1, HUGE_VAL);
  for (int f = 1; f <= nf; ++f) {
    const double l = g.face_boundary_length(f);
    if (l > 0) width[f] = 2 * g.face_area(f) / l;
  }
  // The unit direction a curve leaves point p in; zero when it does not end there.
  const auto leaving = [&](int c, int p) -> Vec3 {
    if (g.curve_degenerated(c)) return Vec3::Zero();
    double t0, t1;
    g.curve_range(c, t0, t1);
    Vec3 d = Vec3::Zero();
    if (g.curve_start_point(c) == p) d = g.curve_tangent(c, t0);
    else if (g.curve_end_point(c) == p) d = -g.curve_tangent(c, t1);
    const double n = d.norm();
    return n > 0 && std::isfinite(n) ? Vec3(d / n) : Vec3::Zero();
  };
  for (int c = 1; c <= nc; ++c) {
    if (t.curve_kind[c - 1] != CurveKind::Virtual || uses[c].empty()) continue;
    double t0, t1;
    g.curve_range(c, t0, t1);
    const Use& u = uses[c][0];
    const double h = size(u.face, g.eval_pcurve(c, u.face, u.side, 0.5 * (t0 + t1)));
    if (h > 0 && g.curve_length(c) < h) {
      ++r.short_curve;
      continue;
    }
    if (h > 0 && std::any_of(uses[c].begin(), uses[c].end(), [&](const Use& x) { return width[x.face] < h; })) {
      ++r.narrow_face;
      continue;
    }
    bool sharp = false;
    for (int p : {g.curve_start_point(c), g.curve_end_point(c)}) {
      const Vec3 d = leaving(c, p);
      if (d.isZero()) continue;
      for (const Use& x : uses[c])
        for (int other : curves_of[x.face]) {
          if (other == c) continue;
          const Vec3 e = leaving(other, p);
          if (!e.isZero() && std::acos(std::clamp(d.dot(e), -1.0, 1.0)) * 180 / kPi < kSliverDeg) sharp = true;
        }
    }
    if (sharp) ++r.small_angle;
    else ++r.smooth;
  }
  return r;
}

}  // namespace sizemesh
