#include "mesher/sharp_corners.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>


namespace sizemesh {
namespace {

constexpr double kWedgeWidth = 0.25;      // wedge width at the first node, in elements
constexpr double kMaxLeadTurn = kPi / 9;  // most a first segment may turn
constexpr double kLeadShare = 0.4;        // most of its curve a first segment may take
constexpr double kPropagate = kPi / 3;    // corners that take the other side's first segment
constexpr double kMaxLead = 6;            // longest first segment, in elements
constexpr double kMinCurve = 8;           // shortest curve, in elements, that takes a long first segment

// One side of a corner: a curve and its end at the corner.
struct Link {
  int curve;
  int end;  // 0: t0, 1: t1
};

// A corner of a face's loop: two curves leaving one B-rep point.
struct Corner {
  Link side[2];
  double alpha;  // angle between the sides' tangents at the point
  double h;      // size there
  double most = std::numeric_limits<double>::infinity();  // longest first segment the deviation bound allows
};

class Leads {
 public:
  Leads(const Geometry& g, const std::vector<CurveSamples>& s) : g_(g), s_(s) {
    out_.assign(s.size(), {0.0, 0.0});
  }

  bool usable(int c) const {
    return c > 0 && static_cast<size_t>(c) < s_.size() && !g_.curve_degenerated(c) && s_[c].S.size() > 2 &&
           s_[c].length() > 0;
  }

  // Unit direction leaving a curve end (zero where it cannot be found).
  Vec3 leaving(Link l) const {
    const CurveSamples& s = s_[l.curve];
    Vec3 d = l.end == 0 ? g_.curve_tangent(l.curve, s.t.front()) : Vec3(-g_.curve_tangent(l.curve, s.t.back()));
    if (!(d.norm() > 0)) {
      const size_t m = s.t.size() - 1;
      d = l.end == 0 ? Vec3(g_.eval_curve(l.curve, s.t[1]) - g_.eval_curve(l.curve, s.t[0]))
                     : Vec3(g_.eval_curve(l.curve, s.t[m - 1]) - g_.eval_curve(l.curve, s.t[m]));
    }
    return d.norm() > 0 && std::isfinite(d.norm()) ? Vec3(d.normalized()) : Vec3::Zero();
  }

  // The chord within the field's deviation bound on `face` at the point where l ends
  // (SizeField::deviation_chord): on a curved face a first segment longer
  // than this leaves the corner's triangle farther off the surface than
  // asked. No bound where the face is flat or its curvature cannot be evaluated.
  double deviation_cap(Link l, int face, const SizeField& field) const {
    const CurveSamples& s = s_[l.curve];
    Vec2 uv;
    try {
      uv = g_.eval_pcurve(l.curve, face, 0, l.end == 0 ? s.t.front() : s.t.back());
    } catch (const Error&) {
      return std::numeric_limits<double>::infinity();
    }
    return field.deviation_chord(g_, face, uv);
  }

  // Longest first segment: kLeadShare of the curve, turning at most
  // kMaxLeadTurn; none on a curve shorter than kMinCurve elements of size h.
  double room(Link l, double h) const {
    const CurveSamples& s = s_[l.curve];
    const double L = s.length();
    if (L < kMinCurve * h) return 0.0;
    const double turn = l.end == 0 ? sample_at(s.S, sample_pos(s.T, kMaxLeadTurn))
                                   : L - sample_at(s.S, sample_pos(s.T, s.turning - kMaxLeadTurn));
    return std::min(kLeadShare * L, turn);
  }

  double lead(Link l) const { return out_[l.curve][l.end]; }

  // Point at arc length r from a curve end.
  Vec3 at(Link l, double r) const {
    const CurveSamples& s = s_[l.curve];
    return g_.eval_curve(l.curve, sample_at(s.t, sample_pos(s.S, l.end == 0 ? r : s.length() - r)));
  }

  // Element size at arc length r from a curve end: ds / dF of Eq. 1a there.
  double size_at(Link l, double r) const {
    const CurveSamples& s = s_[l.curve];
    const SamplePos p = sample_pos(s.S, l.end == 0 ? r : s.length() - r);
    const double dF = s.F[p.k] - s.F[p.k - 1];
    return dF > 0 ? (s.S[p.k] - s.S[p.k - 1]) / dF : 0.0;
  }

  // Width of a corner's wedge at arc length r along both curves.
  double width(const Corner& c, double r) const { return (at(c.side[0], r) - at(c.side[1], r)).norm(); }

  // First segment of length r at a curve end; false if it was at least that long.
  bool apply(Link l, double r) {
    double& lead = out_[l.curve][l.end];
    if (!(r > lead * (1 + 1e-9))) return false;
    lead = r;
    return true;
  }

  std::vector<std::array<double, 2>> finish() {
    for (size_t c = 1; c < s_.size(); ++c) {
      auto& l = out_[c];
      const double L = s_[c].length(), sum = l[0] + l[1];
      if (sum > 2 * kLeadShare * L) {  // two corners ask for more than the curve has
        l[0] *= 2 * kLeadShare * L / sum;
        l[1] *= 2 * kLeadShare * L / sum;
      }
    }
    return std::move(out_);
  }

 private:
  const Geometry& g_;
  const std::vector<CurveSamples>& s_;
  std::vector<std::array<double, 2>> out_;
};

}  // namespace

std::vector<std::array<double, 2>> corner_leads(const Geometry& g, const std::vector<std::vector<FaceLoop>>& loops,
                                                const std::vector<CurveSamples>& samples, const SizeField& field) {
  const double deviation = field.accuracy().deviation;
  Leads leads(g, samples);
  // Faces on each curve: under a deviation bound a first segment bounds all of them.
  std::vector<std::vector<int>> curve_faces(deviation > 0 ? samples.size() : 0);
  for (size_t f = 1; f < loops.size() && deviation > 0; ++f)
    for (const FaceLoop& loop : loops[f])
      for (const CurveUse& u : loop)
        if (u.curve > 0 && u.curve < static_cast<int>(curve_faces.size())) curve_faces[u.curve].push_back(static_cast<int>(f));
  std::vector<Corner> corners;
  for (size_t f = 1; f < loops.size(); ++f)
    for (const FaceLoop& loop : loops[f]) {
      std::vector<CurveUse> uses;
      for (const CurveUse& u : loop)
        if (leads.usable(u.curve)) uses.push_back(u);
      const size_t n = uses.size();
      if (n < 2) continue;
      for (size_t i = 0; i < n; ++i) {
        const size_t j = (i + 1) % n;
        if (uses[i].curve == uses[j].curve) continue;
        Corner c;
        c.side[0] = {uses[i].curve, uses[i].reversed ? 0 : 1};  // use i ends at the corner
        c.side[1] = {uses[j].curve, uses[j].reversed ? 1 : 0};  // use j starts there
        Vec3 d0, d1;
        try {
          d0 = leads.leaving(c.side[0]);
          d1 = leads.leaving(c.side[1]);
        } catch (const EvaluationError&) {  // no tangent there: not a corner this rule can judge
          continue;
        }
        if (!(d0.norm() > 0) || !(d1.norm() > 0)) continue;
        c.alpha = std::acos(std::clamp(d0.dot(d1), -1.0, 1.0));
        if (c.alpha >= kPropagate) continue;
        const CurveSamples &s0 = samples[c.side[0].curve], &s1 = samples[c.side[1].curve];
        c.h = std::min(c.side[0].end == 0 ? s0.h0 : s0.h1, c.side[1].end == 0 ? s1.h0 : s1.h1);
        if (deviation > 0)
          for (const Link& l : c.side)
            for (int face : curve_faces[l.curve]) c.most = std::min(c.most, leads.deviation_cap(l, face, field));
        if (std::isfinite(c.h) && c.h > 0) corners.push_back(c);
      }
    }

  // Two faces with the same two curves at a corner (the upper and lower
  // skin of a lens-shaped tip) would both close it with the same triangle, an
  // edge in four triangles: such a corner keeps the ordinary discretisation.
  std::map<std::array<int, 4>, int> seen;
  auto key = [](const Corner& c) {
    std::array<int, 4> k{c.side[0].curve, c.side[0].end, c.side[1].curve, c.side[1].end};
    if (k[0] > k[2]) k = {k[2], k[3], k[0], k[1]};
    return k;
  };
  for (const Corner& c : corners) ++seen[key(c)];
  corners.erase(std::remove_if(corners.begin(), corners.end(), [&](const Corner& c) { return seen[key(c)] > 1; }),
                corners.end());

  // Sharp corners, whose wedge is narrower than kWedgeWidth h one element
  // from the point (measured between the curves, so that curves leaving the
  // point tangent to each other count): the first node where a wedge opening
  // at alpha is kWedgeWidth h wide, at most kMaxLead elements out.
  for (const Corner& c : corners) {
    const double most = std::min({kMaxLead * c.h, c.most, leads.room(c.side[0], c.h), leads.room(c.side[1], c.h)});
    try {
      if (!(most > c.h) || leads.width(c, c.h) >= kWedgeWidth * c.h) continue;
    } catch (const EvaluationError&) {  // the kernel cannot evaluate a curve there: equal steps
      continue;
    }
    // The segments after the first are as long as the size where it ends,
    // which grows away from a small corner size: r is found where the wedge
    // is kWedgeWidth times that size wide (a few fixed-point steps).
    double r = most;
    if (c.alpha > 0) {
      r = std::min(most, kWedgeWidth * c.h / std::tan(c.alpha));
      for (int it = 0; it < 4; ++it) {
        const double h = std::max({c.h, leads.size_at(c.side[0], r), leads.size_at(c.side[1], r)});
        r = std::min(most, kWedgeWidth * h / std::tan(c.alpha));
      }
    }
    if (!(r > c.h)) continue;
    leads.apply(c.side[0], r);
    leads.apply(c.side[1], r);
  }
  // Corners under kPropagate with a long first segment on one side only: the same on the other.
  for (int pass = 0; pass < 8; ++pass) {
    bool changed = false;
    for (const Corner& c : corners) {
      const double d0 = leads.lead(c.side[0]), d1 = leads.lead(c.side[1]);
      const int lo = d0 < d1 ? 0 : 1;
      const double r = std::min(std::max(d0, d1), leads.room(c.side[lo], c.h));
      if (r > c.h && r > 1.1 * std::min(d0, d1)) changed |= leads.apply(c.side[lo], r);
    }
    if (!changed) break;
  }
  return leads.finish();
}

}  // namespace sizemesh
