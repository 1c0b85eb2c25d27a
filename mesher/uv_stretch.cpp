#include "mesher/uv_stretch.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace sizemesh {
namespace {

constexpr int kIntervals = 96;  // knots of a map
constexpr int kLines = 8;       // lines across the face averaged into a direction's speed
constexpr size_t kMaxOwnKnots = 4 * kIntervals;  // surface knots a map takes at most

// The knot interval [i - 1, i] of increasing knots that holds x; outside
// the range, the end interval (whose line then extends the map).
size_t interval(const std::vector<double>& knots, double x) {
  const size_t i = std::upper_bound(knots.begin(), knots.end(), x) - knots.begin();
  return std::clamp<size_t>(i, 1, knots.size() - 1);
}

}  // namespace

double UvStretch::Axis::interpolate(const std::vector<double>& from, const std::vector<double>& to, double x) {
  const size_t i = interval(from, x);
  const double t = (x - from[i - 1]) / (from[i] - from[i - 1]);
  return to[i - 1] + t * (to[i] - to[i - 1]);
}

double UvStretch::Axis::slope(double x) const {
  if (w.empty()) return 1.0;
  const size_t i = interval(w, x);
  return (u[i] - u[i - 1]) / (w[i] - w[i - 1]);
}

UvStretch::UvStretch(const Geometry& g, int face) {
  // The mean speed of an elementary surface along u is the same on every
  // v-line and the other way round (its metric separates): both maps would be
  // the identity, found at the cost of the samples below.
  if (g.face_elementary(face)) return;
  const UVBox box = g.face_uv_bounds(face);
  const double period[2] = {g.face_period_u(face), g.face_period_v(face)};
  for (int d = 0; d < 2; ++d) {
    if (period[d] > 0) continue;
    const int o = 1 - d;
    const double lo = box.lo[d], hi = box.hi[d];
    if (!(hi > lo) || !std::isfinite(hi - lo)) continue;
    // The map's knots: even steps, and the surface's own knots, across which
    // its speed may jump (a B-spline only C0 in its parameter there): a map
    // interval then never straddles a jump. A surface with very many knots
    // gives every few of them.
    std::vector<double> knot(kIntervals + 1);
    for (int i = 0; i <= kIntervals; ++i) knot[i] = lo + (hi - lo) * i / kIntervals;
    const std::vector<double> own = g.face_knots(face, d);
    const size_t every = own.size() / kMaxOwnKnots + 1;
    for (size_t i = 0; i < own.size(); i += every) knot.push_back(own[i]);
    std::sort(knot.begin(), knot.end());
    const double apart = 1e-9 * (hi - lo);
    knot.erase(std::unique(knot.begin(), knot.end(), [&](double a, double b) { return b - a <= apart; }), knot.end());
    knot.back() = hi;
    const size_t n = knot.size() - 1;  // intervals
    // Speed along direction d in the middle of each interval (never on a
    // knot, where it may take either side's value), then at both ends of the
    // range (where a speed falling to zero at the face's edge shows, which
    // the map must follow), on lines across the face. The map integrates the
    // first n; whether to stretch looks at all.
    const size_t m = n + 2;
    std::vector<double> speed(m, 0.0);
    std::vector<std::array<double, kLines>> line(m);
    bool ok = n > 0;
    for (size_t i = 0; i < m && ok; ++i) {
      const double at = i < n ? 0.5 * (knot[i] + knot[i + 1]) : i == n ? lo : hi;
      for (int j = 0; j < kLines && ok; ++j) {
        Vec2 uv;
        uv[d] = at;
        uv[o] = box.lo[o] + (box.hi[o] - box.lo[o]) * (j + 0.5) / kLines;
        try {
          const SurfaceD1 s = g.eval_face(face, uv);
          line[i][j] = (d == 0 ? s.du : s.dv).norm();
          ok = std::isfinite(line[i][j]);
        } catch (const EvaluationError&) {  // not evaluable here: the face keeps its own uv
          ok = false;
        }
        speed[i] += line[i][j] / kLines;
      }
    }
    if (!ok) continue;
    const double top = *std::max_element(speed.begin(), speed.end());
    const double bottom = *std::min_element(speed.begin(), speed.end());
    if (!(top > 0) || !(top > kRatio * bottom)) continue;
    // Keeps the map strictly increasing where the speed vanishes, and no
    // higher: a span a thousandth as fast as the fastest (a fairing's
    // rounded corner) keeps its true width, and a span where the surface
    // stands still (a trailing edge written as a strip) gets next to none.
    const double floor = 1e-6 * top;
    // The mean must carry the variation: on every line, the speed left after
    // stretching (line / mean) varies at most half as much as the mean does.
    // Where lines differ in shape (a speed that grows along one side only),
    // a map of the mean would squeeze some of them.
    double left = 1;
    for (int j = 0; j < kLines; ++j) {
      double a = HUGE_VAL, b = 0;
      for (size_t i = 0; i < m; ++i) {
        const double r = std::max(line[i][j], floor) / std::max(speed[i], floor);
        a = std::min(a, r);
        b = std::max(b, r);
      }
      left = std::max(left, b / a);
    }
    if (!(2 * left <= top / std::max(bottom, floor))) continue;
    // w(u): the integral of the speed (floored so the map stays strictly
    // increasing), by the midpoint rule, scaled back onto [lo, hi].
    std::vector<double> w(n + 1, 0.0);
    for (size_t i = 0; i < n; ++i) w[i + 1] = w[i] + std::max(speed[i], floor) * (knot[i + 1] - knot[i]);
    const double total = w.back();
    for (double& x : w) x = lo + (hi - lo) * (x / total);
    w.back() = hi;
    axis_[d].u = std::move(knot);
    axis_[d].w = std::move(w);
  }
}

}  // namespace sizemesh
