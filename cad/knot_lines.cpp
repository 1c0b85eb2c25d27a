// Where a B-spline surface folds, jumps or collapses along its knot lines, sampled (cad/knot_lines.h).
#include "cad/knot_lines.h"

#include <gp_Dir.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sizemesh::detail {
namespace {

constexpr int kSamples = 24;          // along each knot line
constexpr double kFoldCos = 0.5;      // normals more than 60 deg apart across the band
constexpr double kJump = 3.0;        // parametric speed ratio across a knot line

// The point of s on the iso-line `along_u ? u = t : v = t` at w of the other parameter.
gp_Pnt iso_point(const Geom_Surface& s, bool along_u, double t, double w) {
  return along_u ? s.Value(t, w) : s.Value(w, t);
}

// Unit normal of s at (u, v); false where it is undefined.
bool normal_at(const Geom_Surface& s, double u, double v, gp_Dir& n) {
  gp_Pnt p;
  gp_Vec du, dv;
  s.D1(u, v, p, du, dv);
  const gp_Vec c = du.Crossed(dv);
  if (!(c.Magnitude() > 1e-300)) return false;
  n = gp_Dir(c);
  return true;
}

// Length over the surface across the strip between the iso-lines t_a and
// t_b at w of the other parameter (a polyline of `steps` pieces; 1: the
// straight distance).
double width_at(const Geom_BSplineSurface& s, bool along_u, double t_a, double t_b, double w, int steps) {
  double length = 0;
  gp_Pnt last = iso_point(s, along_u, t_a, w);
  for (int i = 1; i <= steps; ++i) {
    const gp_Pnt p = iso_point(s, along_u, t_a + (t_b - t_a) * i / steps, w);
    length += p.Distance(last);
    last = p;
  }
  return length;
}

// width_at, at samples over the other parameter's range [lo, hi].
std::vector<double> strip_widths(const Geom_BSplineSurface& s, bool along_u, double t_a, double t_b, double lo,
                                 double hi, int steps) {
  std::vector<double> d;
  for (int j = 0; j <= kSamples / 3; ++j)
    d.push_back(width_at(s, along_u, t_a, t_b, lo + (hi - lo) * (j + 0.5) / (kSamples / 3 + 1), steps));
  return d;
}

// Median distance in space between the iso-lines t_a and t_b (u = t when
// along_u), over the other parameter's range [lo, hi]: the width of the strip
// a split between them would leave.
double strip_width(const Geom_BSplineSurface& s, bool along_u, double t_a, double t_b, double lo, double hi) {
  std::vector<double> d = strip_widths(s, along_u, t_a, t_b, lo, hi, 1);
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

// True when the strip between the iso-lines t_a and t_b narrows inside to
// under `band`, wider than `band` on both sides of that place, and there its
// two sides meet at less than kSliverDeg (its width changes by less than
// tan(kSliverDeg) per unit length along it, either way): a blunt trailing
// edge's base whose thickness passes through zero along the span, a face
// there thinner than any element and its triangles slivers. A cap narrowing
// to its round nose (its sides meeting at a large angle), a strip narrow all
// along, or one tapering into a span collapsed onto a curve is no pinch.
bool strip_pinches(const Geom_BSplineSurface& s, bool along_u, double t_a, double t_b, double lo, double hi,
                   double band) {
  constexpr double kSliverDeg = 12;
  const double slope = std::tan(kSliverDeg * M_PI / 180), collapsed = 1e-3 * band;
  constexpr int kAcross = 8;  // widths over the surface: a polyline of this many pieces across
  const std::vector<double> d = strip_widths(s, along_u, t_a, t_b, lo, hi, kAcross);
  const double step = (hi - lo) / d.size();  // between samples
  for (size_t i = 1; i + 1 < d.size(); ++i) {
    if (!(d[i] < band)) continue;
    bool wide[2] = {false, false};
    for (int k = 0; k < 2; ++k)
      for (size_t j = i; k == 0 ? j-- > 0 : ++j < d.size();) {
        if (!(d[j] > collapsed)) break;
        if (d[j] > band) {
          wide[k] = true;
          break;
        }
      }
    if (!wide[0] || !wide[1]) continue;
    // The slope an eighth of a sample step either way.
    const double w = lo + step * (i + 0.5);
    const gp_Pnt here = iso_point(s, along_u, t_a, w);
    bool sliver = true;
    for (const double dw : {-step / 8, step / 8}) {
      const double run = here.Distance(iso_point(s, along_u, t_a, w + dw));
      sliver = sliver && std::abs(width_at(s, along_u, t_a, t_b, w + dw, kAcross) - d[i]) < slope * run;
    }
    if (sliver) return true;
  }
  return false;
}

// Largest distance of a sample of `a` from the polyline `b`.
double distance_to(const std::vector<gp_Pnt>& a, const std::vector<gp_Pnt>& b) {
  double farthest = 0;
  for (const gp_Pnt& p : a) {
    double nearest = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i + 1 < b.size(); ++i) {
      const gp_Vec e(b[i], b[i + 1]), w(b[i], p);
      const double ee = e.SquareMagnitude(), t = ee > 0 ? std::clamp(w.Dot(e) / ee, 0.0, 1.0) : 0.0;
      nearest = std::min(nearest, w.Subtracted(e.Multiplied(t)).Magnitude());
    }
    farthest = std::max(farthest, nearest);
  }
  return farthest;
}

}  // namespace

double splits_at(const Geom_BSplineSurface& s, bool along_u, double t, double lo, double hi, double t_lo,
                 double t_hi, double band, bool crease_only) {
  std::vector<double> ratios;
  double fold = 0;
  int folded = 0, defined = 0;
  for (int j = 0; j <= kSamples; ++j) {
    const double w = lo + (hi - lo) * (j + 0.5) / (kSamples + 1);
    double side[2], speed[2];
    for (int k = 0; k < 2; ++k) {  // parameter step that covers `band` in space on each side
      const double sign = k == 0 ? -1 : 1;
      const double e = 1e-6 * (t_hi - t_lo);
      gp_Pnt p;
      gp_Vec du, dv;
      if (along_u) s.D1(t + sign * e, w, p, du, dv);
      else s.D1(w, t + sign * e, p, du, dv);
      speed[k] = (along_u ? du : dv).Magnitude();
      double step = speed[k] > 0 ? band / speed[k] : (t_hi - t_lo);
      step = std::min(step, k == 0 ? t - t_lo : t_hi - t);
      side[k] = t + sign * step;
    }
    const double slow = std::min(speed[0], speed[1]), fast = std::max(speed[0], speed[1]);
    if (slow > 0) ratios.push_back(fast / slow);
    gp_Dir n0, n1;
    const bool ok = along_u ? normal_at(s, side[0], w, n0) && normal_at(s, side[1], w, n1)
                            : normal_at(s, w, side[0], n0) && normal_at(s, w, side[1], n1);
    defined += ok;
    if (ok && n0.Dot(n1) < kFoldCos) fold = std::max(fold, 1 - n0.Dot(n1)), ++folded;
  }
  // Most of the line, counted where the surface has a normal on both sides
  // (a section whose trailing-edge spans collapse to a point has none there),
  // and that over a third of the line at least.
  if (crease_only) return 3 * defined > kSamples + 1 && 2 * folded > defined ? 2 + fold : 0;
  if (fold > 0) return 2 + fold;
  // A jump along most of the line (the median: a pole at one end of it has
  // any ratio at all).
  if (ratios.empty()) return 0;
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  return ratios[ratios.size() / 2] > kJump ? 1 : 0;
}

bool flat_strip(const Geom_BSplineSurface& s, bool along_u, double t_a, double t_b, double lo, double hi,
                double band) {
  double widest = 0;
  for (int j = 0; j <= kSamples; ++j) {
    const double w = lo + (hi - lo) * (j + 0.5) / (kSamples + 1);
    widest = std::max(widest, iso_point(s, along_u, t_a, w).Distance(iso_point(s, along_u, t_b, w)));
  }
  if (!(widest > band)) return false;
  std::vector<gp_Pnt> points;
  gp_XYZ normal(0, 0, 0);
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= kSamples; ++j) {
      const double t = t_a + (t_b - t_a) * (i + 0.5) / 5, w = lo + (hi - lo) * (j + 0.5) / (kSamples + 1);
      const double u = along_u ? t : w, v = along_u ? w : t;
      points.push_back(s.Value(u, v));
      gp_Dir n;
      if (!normal_at(s, u, v, n)) continue;
      normal += n.XYZ() * (normal.Dot(n.XYZ()) < 0 ? -1.0 : 1.0);
    }
  if (!(normal.Modulus() > 0)) return false;
  normal.Normalize();
  gp_XYZ centre(0, 0, 0);
  for (const auto& p : points) centre += p.XYZ();
  centre /= static_cast<double>(points.size());
  for (const auto& p : points)
    if (std::abs((p.XYZ() - centre).Dot(normal)) > band) return false;
  return true;
}

bool collapsed_strip(const Geom_BSplineSurface& s, bool along_u, double t_a, double t_b, double lo, double hi,
                     double tol) {
  for (int j = 0; j <= kSamples; ++j) {
    const double w = lo + (hi - lo) * j / kSamples;
    const gp_Pnt a = iso_point(s, along_u, t_a, w);
    for (int i = 1; i <= 4; ++i) {
      const double t = t_a + (t_b - t_a) * i / 4;
      if (iso_point(s, along_u, t, w).Distance(a) > tol) return false;
    }
  }
  return true;
}

double fold_back_gap(const Geom_BSplineSurface& s, bool along_u, double c, double t0, double t, double t1,
                     double tol) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  auto at = [&](double w) { return iso_point(s, along_u, c, w); };
  if (at(t0).Distance(at(t1)) > tol) return kInf;
  // The line turns back at t: its steps just before and just after point
  // opposite ways (the samples below are only taken where it does).
  const double e = 1e-3 * std::min(t - t0, t1 - t);
  const gp_Vec before(at(t - e), at(t)), after(at(t), at(t + e));
  if (!(before.Magnitude() > 0 && after.Magnitude() > 0) || before.Dot(after) > -0.9 * before.Magnitude() * after.Magnitude())
    return kInf;
  constexpr int n = 8 * kSamples;
  std::vector<gp_Pnt> part[2];
  double length[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const double a = k == 0 ? t0 : t, b = k == 0 ? t : t1;
    for (int i = 0; i <= n; ++i) {
      const double w = a + (b - a) * i / n;
      part[k].push_back(at(w));
      if (i > 0) length[k] += part[k][i].Distance(part[k][i - 1]);
    }
  }
  if (!(std::min(length[0], length[1]) > 10 * tol)) return kInf;
  return std::max({part[0].front().Distance(part[1].back()), distance_to(part[0], part[1]),
                   distance_to(part[1], part[0])});
}

std::vector<double> kept_splits(const Geom_BSplineSurface& s, bool along_u, std::vector<std::pair<double, double>> cand,
                                double t0, double t1, double lo, double hi, double min_width, double border_width) {
  for (bool dropped = true; dropped && !cand.empty();) {
    dropped = false;
    double narrowest = min_width;
    size_t drop = cand.size();
    for (size_t i = 0; i <= cand.size(); ++i) {  // strip i lies between line i-1 and line i
      const double a = i == 0 ? t0 : cand[i - 1].first, b = i == cand.size() ? t1 : cand[i].first;
      const double lower = i == 0 ? cand[0].second : i == cand.size() ? cand[i - 1].second
                                                                       : std::min(cand[i - 1].second, cand[i].second);
      const size_t weaker = i == 0 ? 0 : i == cand.size() ? i - 1 : (cand[i - 1].second <= cand[i].second ? i - 1 : i);
      // A fold by the border stays, unless the strip behind it pinches
      // (strip_pinches: a face there would be thinner than any element).
      if ((i == 0 || i == cand.size()) && lower >= 2 && !strip_pinches(s, along_u, a, b, lo, hi, border_width))
        continue;
      const double w = strip_width(s, along_u, a, b, lo, hi);
      if (w < narrowest) narrowest = w, drop = weaker;
    }
    if (drop < cand.size()) cand.erase(cand.begin() + drop), dropped = true;
  }
  std::vector<double> out;
  for (const auto& c : cand) out.push_back(c.first);
  return out;
}

std::vector<double> knots_inside(const Geom_BSplineSurface& s, bool along_u, double t0, double t1) {
  std::vector<double> out;
  const double eps = 1e-9 * (t1 - t0);
  const int knots = along_u ? s.NbUKnots() : s.NbVKnots();
  for (int k = 1; k <= knots; ++k) {
    const double t = along_u ? s.UKnot(k) : s.VKnot(k);
    if (t > t0 + eps && t < t1 - eps) out.push_back(t);
  }
  return out;
}

}  // namespace sizemesh::detail
