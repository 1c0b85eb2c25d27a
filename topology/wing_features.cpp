#include "topology/wing_features.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace sizemesh {
namespace {

constexpr int kSamples = 64;            // points per curve the chords are measured to
constexpr double kAcross = 0.7;         // |cos| between a leading edge and the way to its trailing edge
constexpr double kRadiusOverChord = 0.1;  // a leading edge's radius of curvature is under this share of its chord
constexpr double kLengthOverChord = 0.02;  // and its length at least this share

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

// Distance from x to the polyline p.
double to_polyline(const std::vector<Vec3>& p, const Vec3& x) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i + 1 < p.size(); ++i) {
    const Vec3 e = p[i + 1] - p[i];
    const double ee = e.squaredNorm(), t = ee > 0 ? std::clamp((x - p[i]).dot(e) / ee, 0.0, 1.0) : 0.0;
    best = std::min(best, (p[i] + t * e - x).squaredNorm());
  }
  if (p.size() == 1) best = (p[0] - x).squaredNorm();
  return std::sqrt(best);
}

double to_chain(const std::vector<std::vector<Vec3>>& chain, const Vec3& x) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : chain) best = std::min(best, to_polyline(p, x));
  return best;
}

// Samples of curve c at kSamples + 1 parameters, its ends included.
std::vector<Vec3> polyline(const Geometry& g, int c) {
  double t0, t1;
  g.curve_range(c, t0, t1);
  std::vector<Vec3> out;
  for (int i = 0; i <= kSamples; ++i) out.push_back(g.eval_curve(c, t0 + (t1 - t0) * i / kSamples));
  return out;
}

}  // namespace

double WingFeatures::base_width_at(const Vec3& x, int b) const {
  return to_chain(bases[b].side[0], x) + to_chain(bases[b].side[1], x);
}

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
  // Blunt bases: composites bounded by two long chains of creases (a crease
  // continues into the next curve at a point where they leave it opposite
  // ways), narrow against their length. Their creases are trailing-edge
  // candidates of the skins across them.
  // The composite across curve c (two faces) from composite `comp`.
  auto across = [&](int c, int comp) {
    return root(uses[c][0].face) == comp ? root(uses[c][1].face) : root(uses[c][0].face);
  };
  // The B-rep faces of composite `comp`, in id order.
  auto faces_of = [&](int comp) {
    std::vector<int> out;
    for (int f = 1; f <= g.num_faces(); ++f)
      if (root(f) == comp) out.push_back(f);
    return out;
  };
  struct Candidate {
    int comp;
    std::vector<int> chain[2];
    std::vector<std::vector<Vec3>> lines[2];  // each chain's curves as polylines
    double width, width_min, width_max;       // median, least and most over both chains' points
  };
  std::vector<Candidate> candidates;
  {
    std::map<int, std::vector<int>> creases;  // composite -> its crease curves
    for (const auto& [c, u] : uses) {
      if (u.size() != 2 || kind(c) != CurveKind::Angle || g.curve_degenerated(c)) continue;
      if (!(turn(c) >= WingFeatures::kBaseTurnDeg) || turn(c) >= WingFeatures::kTrailingTurnDeg) continue;
      const int a = root(u[0].face), b = root(u[1].face);
      if (a == b) continue;
      creases[a].push_back(c), creases[b].push_back(c);
    }
    auto leaving = [&](int c, int pt) {  // direction curve c leaves point pt
      double t0, t1;
      g.curve_range(c, t0, t1);
      return g.curve_start_point(c) == pt ? Vec3(g.curve_tangent(c, t0)) : Vec3(-g.curve_tangent(c, t1));
    };
    for (const auto& [comp, curves] : creases) {
      std::map<int, int> up;
      for (int c : curves) up[c] = c;
      auto top = [&](int c) {
        while (up[c] != c) c = up[c] = up[up[c]];
        return c;
      };
      for (size_t i = 0; i < curves.size(); ++i)
        for (size_t j = i + 1; j < curves.size(); ++j)
          for (int p : {g.curve_start_point(curves[i]), g.curve_end_point(curves[i])})
            if (p > 0 && (p == g.curve_start_point(curves[j]) || p == g.curve_end_point(curves[j]))) {
              const Vec3 a = leaving(curves[i], p), b = leaving(curves[j], p);
              if (a.dot(b) < -0.8 * a.norm() * b.norm()) up[top(curves[i])] = top(curves[j]);
            }
      // The two longest chains are its sides (its ends, crossing the strip,
      // may be creases too).
      std::map<int, std::vector<int>> by_top;
      for (int c : curves) by_top[top(c)].push_back(c);
      std::vector<std::pair<double, std::vector<int>>> chains;
      for (auto& [t, chain] : by_top) {
        double length = 0;
        for (int c : chain) length += g.curve_length(c);
        chains.push_back({length, std::move(chain)});
      }
      if (chains.size() < 2) continue;
      std::partial_sort(chains.begin(), chains.begin() + 2, chains.end(),
                        [](const auto& a, const auto& b) { return a.first > b.first; });
      Candidate cand{comp, {chains[0].second, chains[1].second}, {}, 0, 0, 0};
      const double length[2] = {chains[0].first, chains[1].first};
      for (int k = 0; k < 2; ++k)
        for (int c : cand.chain[k]) cand.lines[k].push_back(polyline(g, c));
      std::vector<double> widths;
      for (int k = 0; k < 2; ++k)
        for (const auto& line : cand.lines[k])
          for (const Vec3& x : line) widths.push_back(to_chain(cand.lines[1 - k], x));
      const auto [lo, hi] = std::minmax_element(widths.begin(), widths.end());
      cand.width_min = *lo, cand.width_max = *hi;
      std::nth_element(widths.begin(), widths.begin() + widths.size() / 2, widths.end());
      cand.width = widths[widths.size() / 2];
      // A strip: long against its width, and no more area than the width
      // times its length (twice, for a strip that widens along the span).
      double area = 0;
      for (int f : faces_of(comp)) area += g.face_area(f);
      if (!(cand.width > 0) || std::min(length[0], length[1]) < WingFeatures::kBaseAspect * cand.width ||
          area > cand.width * (length[0] + length[1]))
        continue;
      for (int k = 0; k < 2; ++k)
        for (int c : cand.chain[k])
          for (const Vec3& x : samples(g, c))
            te_points.push_back(x), te_comp.push_back(across(c, comp)), te_curve.push_back(c);
      candidates.push_back(std::move(cand));
    }
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
      if (!(chord > 0) || !(tangent.norm() > 0) || std::abs(tangent.normalized().dot(to / chord)) > kAcross ||
          g.curve_length(c) < kLengthOverChord * chord)
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
  // The bases whose creases all border skins with a leading edge, no wider
  // than kBaseOverChord of the chord there: their creases are trailing edges.
  const std::set<int> winged(w.leading_composite.begin(), w.leading_composite.end());
  for (Candidate& cand : candidates) {
    bool ok = true;
    std::vector<double> chords;
    for (int k = 0; k < 2 && ok; ++k)
      for (int c : cand.chain[k]) {
        const int skin = across(c, cand.comp);
        if (!winged.count(skin)) {
          ok = false;
          break;
        }
        for (const Vec3& x : samples(g, c)) chords.push_back(w.chord_at(x, skin, false));
      }
    if (!ok) continue;
    std::nth_element(chords.begin(), chords.begin() + chords.size() / 2, chords.end());
    if (!(cand.width <= WingFeatures::kBaseOverChord * chords[chords.size() / 2])) continue;
    WingFeatures::Base base;
    base.faces = faces_of(cand.comp);
    for (int k = 0; k < 2; ++k) base.side[k] = std::move(cand.lines[k]);
    base.width_min = cand.width_min, base.width_max = cand.width_max;
    w.bases.push_back(std::move(base));
    for (int k = 0; k < 2; ++k)
      for (int c : cand.chain[k]) {
        w.trailing.push_back(c);
        w.trailing_curve_composite.push_back(across(c, cand.comp));
        w.trailing_length += g.curve_length(c);
      }
  }
  // Tips: caps closed by the skins (and blunt bases) alone, a leading edge ending on them.
  std::set<int> base_comps, le_ends;
  for (const WingFeatures::Base& b : w.bases) base_comps.insert(root(b.faces[0]));
  for (int c : w.leading) le_ends.insert(g.curve_start_point(c)), le_ends.insert(g.curve_end_point(c));
  std::map<int, std::vector<int>> border;  // composite -> curves on its border
  std::set<int> open;                      // composites with a border curve to anything else
  for (const auto& [c, u] : uses) {
    if (g.curve_degenerated(c)) continue;
    std::set<int> comps;
    for (const Use& side : u) comps.insert(root(side.face));
    if (comps.size() == 1 && u.size() == 2) continue;  // inside one composite
    for (const Use& side : u) {
      const int comp = root(side.face);
      border[comp].push_back(c);
      // Across a curve between classes (the cap on a symmetry plane, a far
      // field) the cap is no wing's.
      bool skins = u.size() == 2 && kind(c) != CurveKind::Marker;
      for (const Use& other : u)
        if (root(other.face) != comp)
          skins = skins && (winged.count(root(other.face)) || base_comps.count(root(other.face)));
      if (!skins) open.insert(comp);
    }
  }
  for (const auto& [comp, curves] : border) {
    if (winged.count(comp) || base_comps.count(comp) || open.count(comp)) continue;
    bool le_end = false;
    std::vector<Vec3> rim;
    for (int c : curves) {
      le_end = le_end || le_ends.count(g.curve_start_point(c)) || le_ends.count(g.curve_end_point(c));
      for (const Vec3& x : samples(g, c)) rim.push_back(x);
    }
    if (!le_end) continue;
    WingFeatures::Tip tip;
    for (size_t i = 0; i < rim.size(); ++i)
      for (size_t j = i + 1; j < rim.size(); ++j) tip.chord = std::max(tip.chord, (rim[i] - rim[j]).norm());
    tip.faces = faces_of(comp);
    w.tips.push_back(std::move(tip));
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
