#include "mesher/discretise_curves.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "mesher/sharp_corners.h"

namespace sizemesh {
namespace {

// Most a single segment may turn: keeps loops valid in uv when h exceeds a curve's radius.
constexpr double kMaxTurnPerSegment = kPi / 3;
// Guard against a size map far below the model's scale.
constexpr int kMaxSegments = 1000000;

// A curve sampled at m+1 equal parameter steps: Eq. 1a's integral of ds/h by
// the trapezoid rule on chords, arc length and tangent turning.
CurveSamples sample_curve(const Geometry& g, const SizeField& h, int curve, int face, int m,
                          long long& queries) {
  double t0, t1;
  g.curve_range(curve, t0, t1);
  CurveSamples s;
  s.t.resize(m + 1);
  s.F.assign(m + 1, 0.0);
  std::vector<Vec3> p(m + 1);
  std::vector<double> hs(m + 1);
  int hint = -1;
  for (int k = 0; k <= m; ++k) {
    s.t[k] = t0 + (t1 - t0) * k / m;
    p[k] = g.eval_curve(curve, s.t[k]);
    double hk = 0;
    if (face > 0) {
      try {
        hk = h.at(face, g.eval_pcurve(curve, face, 0, s.t[k]), hint);
      } catch (const Error&) {  // no pcurve or size there: the size at the point in space
        hk = 0;
      }
    }
    if (!(hk > 0) || !std::isfinite(hk)) hk = h.at_xyz(p[k]);
    ++queries;
    hs[k] = hk > 0 && std::isfinite(hk) ? hk : std::numeric_limits<double>::infinity();  // no size: no bound
  }
  s.S.assign(m + 1, 0.0);
  s.T.assign(m + 1, 0.0);
  s.h0 = hs[0];
  s.h1 = hs[m];
  for (int k = 1; k <= m; ++k) {
    const double ds = (p[k] - p[k - 1]).norm();
    s.F[k] = s.F[k - 1] + 0.5 * ds * (1.0 / hs[k - 1] + 1.0 / hs[k]);  // Eq. 1a
    s.S[k] = s.S[k - 1] + ds;
  }
  // Turning on chords a quarter of the local size long, or a 32nd of the
  // curve where that is shorter: a curve that wobbles far below its elements
  // (a fold line whose samples turn tens of degrees each, thousandths of the
  // size across) does not turn at their scale, while a bend of a radius
  // below the size, or a hole smaller than one element, still does.
  Vec3 prev = Vec3::Zero();
  int anchor = 0;
  for (int k = 1; k <= m; ++k) {
    s.T[k] = s.turning;
    const double chord = std::min(0.25 * std::min(hs[k], hs[anchor]), s.S[m] / 32);
    if (k < m && s.S[k] - s.S[anchor] < chord) continue;
    Vec3 d = p[k] - p[anchor];
    anchor = k;
    if (d.norm() <= 0) continue;
    d.normalize();
    if (prev.norm() > 0) s.turning += std::acos(std::clamp(prev.dot(d), -1.0, 1.0));
    s.T[k] = s.turning;
    prev = d;
  }
  return s;
}

// Parameters of a curve's n+1 nodes. Between its ends, or between the ends of
// the long first segments lead[0] (at t0) and lead[1] (at t1) where a sharp
// corner asks for them, nodes sit at equal steps of the metric length (Eq. 1b).
std::vector<double> place_nodes(const CurveSamples& s, int n, const std::array<double, 2>& lead) {
  const bool a = lead[0] > 0, b = lead[1] > 0;
  const SamplePos ia = a ? sample_pos(s.S, lead[0]) : SamplePos{1, 0.0};
  const SamplePos ib = b ? sample_pos(s.S, s.S.back() - lead[1]) : SamplePos{s.t.size() - 1, 1.0};
  const int mid = n - a - b;
  std::vector<double> t;
  t.reserve(n + 1);
  t.push_back(s.t.front());
  const double Fa = sample_at(s.F, ia), Fb = sample_at(s.F, ib);
  for (int i = a ? 0 : 1; i <= (b ? mid : mid - 1); ++i)
    t.push_back(sample_at(s.t, sample_pos(s.F, Fa + (Fb - Fa) * i / mid)));
  t.push_back(s.t.back());
  if (a) t[1] = sample_at(s.t, ia);
  if (b) t[n - 1] = sample_at(s.t, ib);
  return t;
}

}  // namespace

CurveMesh discretise_curves(const Geometry& g, const SizeField& h) {
  const int nc = g.num_curves(), np = g.num_points(), nf = g.num_faces();
  CurveMesh out;
  out.point_node.assign(np + 1, -1);
  out.curves.resize(nc + 1);
  for (int p = 1; p <= np; ++p) {
    out.point_node[p] = static_cast<int>(out.xyz.size());
    out.xyz.push_back(g.point_xyz(p));
    out.node_dim.push_back(0);
    out.node_entity.push_back(p);
  }

  // One face per curve to sample h through its pcurve; and every face's loops.
  std::vector<int> curve_face(nc + 1, 0);
  std::vector<std::vector<FaceLoop>> loops(nf + 1);
  for (int f = 1; f <= nf; ++f) {
    loops[f] = g.face_loops(f);
    for (const FaceLoop& l : loops[f])
      for (const CurveUse& u : l)
        if (curve_face[u.curve] == 0 && u.side == 0) curve_face[u.curve] = f;
  }

  // Segment counts, Eq. 1a; sampled per curve in parallel.
  std::vector<int> n(nc + 1, 0);
  std::vector<CurveSamples> sampled(nc + 1);
  std::vector<long long> queries(nc + 1, 0);
  tbb::parallel_for(1, nc + 1, [&](int c) {
    if (g.curve_degenerated(c)) return;
    int nn = 1;
    try {
      CurveSamples coarse = sample_curve(g, h, c, curve_face[c], 32, queries[c]);
      const int m = static_cast<int>(std::clamp(8 * coarse.F.back() + 32, 32.0, 4000.0));
      sampled[c] = m > 32 ? sample_curve(g, h, c, curve_face[c], m, queries[c]) : std::move(coarse);
      const double integral = std::min(sampled[c].F.back(), double(kMaxSegments));
      nn = std::max(1, static_cast<int>(std::lround(integral)));
      nn = std::max(nn, static_cast<int>(std::ceil(sampled[c].turning / kMaxTurnPerSegment - 1e-9)));
    } catch (const EvaluationError&) {  // the kernel cannot evaluate it: equal parameter steps
      sampled[c] = CurveSamples();
      double t0, t1;
      g.curve_range(c, t0, t1);
      for (int k = 0; k <= 8; ++k) {
        sampled[c].t.push_back(t0 + (t1 - t0) * k / 8);
        sampled[c].F.push_back(k);
      }
    }
    if (g.curve_start_point(c) == g.curve_end_point(c)) nn = std::max(nn, 3);
    n[c] = nn;
  });
  for (int c = 1; c <= nc; ++c) out.size_queries += queries[c];

  // Sharp corners (mesher/sharp_corners.h): long first segments; the rest of
  // such a curve is counted again (Eq. 1a) between them.
  const std::vector<std::array<double, 2>> leads = corner_leads(g, loops, sampled, h);
  for (int c = 1; c <= nc; ++c) {
    const auto& lead = leads[c];
    const CurveSamples& s = sampled[c];
    if (lead[0] <= 0 && lead[1] <= 0) continue;
    const SamplePos ia = sample_pos(s.S, lead[0]), ib = sample_pos(s.S, s.S.back() - lead[1]);
    const double metric = std::min(sample_at(s.F, ib) - sample_at(s.F, ia), double(kMaxSegments));
    const double turning = sample_at(s.T, ib) - sample_at(s.T, ia);
    int mid = std::max(1, static_cast<int>(std::lround(metric)));
    mid = std::max(mid, static_cast<int>(std::ceil(turning / kMaxTurnPerSegment - 1e-9)));
    n[c] = mid + (lead[0] > 0) + (lead[1] > 0);
  }

  // Every boundary loop needs at least 3 segments (a seam used twice counts twice).
  for (int f = 1; f <= nf; ++f)
    for (const FaceLoop& l : loops[f]) {
      for (int guard = 0; guard < 8; ++guard) {
        int total = 0, longest = 0;
        for (const CurveUse& u : l) {
          if (g.curve_degenerated(u.curve)) continue;
          total += n[u.curve];
          if (longest == 0 || g.curve_length(u.curve) > g.curve_length(longest)) longest = u.curve;
        }
        if (total >= 3 || longest == 0) break;
        ++n[longest];
      }
    }

  // End nodes are the B-rep points; a curve without end points gets its own.
  auto point_or_new = [&](int p, int c, double t) {
    if (p > 0) return out.point_node[p];
    out.xyz.push_back(g.eval_curve(c, t));
    out.node_dim.push_back(1);
    out.node_entity.push_back(c);
    return static_cast<int>(out.xyz.size()) - 1;
  };
  for (int c = 1; c <= nc; ++c) {
    if (g.curve_degenerated(c) || n[c] == 0) continue;
    CurveNodes& cn = out.curves[c];
    cn.t = place_nodes(sampled[c], n[c], leads[c]);
    cn.node.resize(n[c] + 1);
    cn.node[0] = point_or_new(g.curve_start_point(c), c, cn.t[0]);
    cn.node[n[c]] = point_or_new(g.curve_end_point(c), c, cn.t[n[c]]);
    for (int i = 1; i < n[c]; ++i) {
      cn.node[i] = static_cast<int>(out.xyz.size());
      out.xyz.push_back(g.eval_curve(c, cn.t[i]));
      out.node_dim.push_back(1);
      out.node_entity.push_back(c);
    }
  }
  return out;
}

}  // namespace sizemesh
