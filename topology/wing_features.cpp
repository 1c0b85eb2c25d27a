#include "topology/wing_features.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace sizemesh {
namespace {

constexpr int kSamples = 64;            // points per curve the chords are measured to
constexpr double kAcross = 0.7;         // |cos| between a leading edge and the way to its trailing edge
constexpr double kRadiusOverChord = 0.1;  // a leading edge's radius of curvature is under this share of its chord

struct Use {
  int face, side;
};

// Samples of curve c at kSamples interior parameters.
std::vector<Vec3> samples(const Geometry& g, int c) {
  double t0, t1;
  g.curve_range(c, t0, t1);
  std::vector<Vec3> out;
  for (int i = 0; i < kSamples; ++i) out.push_back(g.eval_curve(c, t0 + (t1 - t0) * (i + 0.5) / kSamples));
  return out;
}

// Nearest of `points` on composite `composite` to x: its index, or -1.
int nearest(const std::vector<Vec3>& points, const std::vector<int>& comp, int composite, const Vec3& x) {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < points.size(); ++i) {
    if (comp[i] != composite) continue;
    const double d = (points[i] - x).squaredNorm();
    if (d < best_d) best_d = d, best = static_cast<int>(i);
  }
  return best;
}

}  // namespace

double WingFeatures::chord_at(const Vec3& x, int composite, bool leading_edge) const {
  const std::vector<Vec3>& other = leading_edge ? trailing_points : leading_points;
  const std::vector<int>& comp = leading_edge ? trailing_composite : leading_composite;
  const int i = nearest(other, comp, composite, x);
  return i < 0 ? 0.0 : (other[i] - x).norm();
}

WingFeatures find_wing_features(const Geometry& g, const Topology& t) {
  WingFeatures w;
  std::map<int, std::vector<Use>> uses;
  for (int f = 1; f <= g.num_faces(); ++f)
    for (const FaceLoop& loop : g.face_loops(f))
      for (const CurveUse& u : loop) uses[u.curve].push_back({f, u.side});
  auto kind = [&](int c) {
    return c >= 1 && c <= static_cast<int>(t.curve_kind.size()) ? t.curve_kind[c - 1] : CurveKind::Angle;
  };
  auto turn = [&](int c) { return c >= 1 && c <= static_cast<int>(t.curve_turn_deg.size()) ? t.curve_turn_deg[c - 1] : -1; };
  // Faces joined across smooth curves (the composite faces, also when the
  // mesher keeps every face apart, --no-composite).
  std::vector<int> parent(g.num_faces() + 1);
  for (int f = 0; f <= g.num_faces(); ++f) parent[f] = f;
  auto root = [&](int f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  };
  for (const auto& [c, u] : uses)
    if (u.size() == 2 && kind(c) == CurveKind::Virtual) parent[root(u[0].face)] = root(u[1].face);

  // Trailing edges: sharp wedges between two faces; samples on each side's composite.
  std::vector<int> sharp;
  std::vector<Vec3> te_points;
  std::vector<int> te_comp, te_curve;
  for (const auto& [c, u] : uses) {
    if (u.size() != 2 || kind(c) != CurveKind::Angle || !(turn(c) >= WingFeatures::kTrailingTurnDeg)) continue;
    if (g.curve_degenerated(c)) continue;
    const std::vector<Vec3> s = samples(g, c);
    const int a = root(u[0].face), b = root(u[1].face);
    for (int comp : {a, b}) {
      for (const Vec3& x : s) te_points.push_back(x), te_comp.push_back(comp), te_curve.push_back(c);
      if (a == b) break;
    }
    sharp.push_back(c);
  }
  // Leading edges: smooth curves across the way to a trailing edge of their
  // composite, curved far more than the chord.
  for (const auto& [c, u] : uses) {
    const CurveKind k = kind(c);
    if ((k != CurveKind::Virtual && k != CurveKind::Seam) || u.empty() || g.curve_degenerated(c)) continue;
    const int comp = root(u[0].face);
    // At a quarter, half and three quarters of its length.
    auto leading_at = [&](double share) {
      double t0, t1;
      g.curve_range(c, t0, t1);
      const double at = t0 + (t1 - t0) * share;
      const Vec3 x = g.eval_curve(c, at);
      const int i = nearest(te_points, te_comp, comp, x);
      if (i < 0) return false;
      const Vec3 to = te_points[i] - x;
      const double chord = to.norm();
      const Vec3 tangent = g.curve_tangent(c, at);
      if (!(chord > 0) || !(tangent.norm() > 0) || std::abs(tangent.normalized().dot(to / chord)) > kAcross)
        return false;
      for (const Use& side : u) {
        double curvature = 0;
        if (!g.max_curvature(side.face, g.eval_pcurve(c, side.face, side.side, at), curvature) ||
            !(curvature * kRadiusOverChord * chord >= 1))
          return false;
      }
      return true;
    };
    if (!leading_at(0.25) || !leading_at(0.5) || !leading_at(0.75)) continue;
    w.leading.push_back(c);
    w.leading_curve_composite.push_back(comp);
    w.leading_length += g.curve_length(c);
    for (const Vec3& x : samples(g, c)) w.leading_points.push_back(x), w.leading_composite.push_back(comp);
  }
  // The trailing edges on a leading edge's faces (a sharp wedge elsewhere,
  // with no leading edge before it, is no wing's).
  for (int c : sharp) {
    bool with_leading = false;
    for (const Use& side : uses[c])
      with_leading = with_leading || std::find(w.leading_composite.begin(), w.leading_composite.end(),
                                               root(side.face)) != w.leading_composite.end();
    if (!with_leading) continue;
    w.trailing.push_back(c);
    w.trailing_curve_composite.push_back(root(uses[c][0].face));
    w.trailing_length += g.curve_length(c);
  }
  for (size_t i = 0; i < te_points.size(); ++i)
    if (std::find(w.trailing.begin(), w.trailing.end(), te_curve[i]) != w.trailing.end())
      w.trailing_points.push_back(te_points[i]), w.trailing_composite.push_back(te_comp[i]);
  // Chord range over both kinds' samples.
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const bool leading : {true, false}) {
    const std::vector<Vec3>& points = leading ? w.leading_points : w.trailing_points;
    const std::vector<int>& comp = leading ? w.leading_composite : w.trailing_composite;
    for (size_t i = 0; i < points.size(); ++i) {
      const double c = w.chord_at(points[i], comp[i], leading);
      if (c > 0) lo = std::min(lo, c), hi = std::max(hi, c);
    }
  }
  if (hi > 0) w.chord_min = lo, w.chord_max = hi;
  return w;
}

}  // namespace sizemesh
