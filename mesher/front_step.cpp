// One step of the advancing front (front.h): the ideal point placed
// equilateral in the metric in uv, or off a pole edge, or in space and
// projected (Tremel procedure 1) when the uv one is poor; the candidates
// ranked by metric distance; the first acceptable triangle added and the
// front updated.
#include "mesher/front.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/predicates.h"

namespace sizemesh::detail {

bool Front::advance(int ei, const Level& lv) {
  const int a = edges_[ei].a, b = edges_[ei].b;
  const Vec2 ua = fm_.uv[a], ub = fm_.uv[b];
  const Vec2 e = ub - ua;
  const Vec2 m = 0.5 * (ua + ub);
  const SurfaceSample sm = fs_.eval(m);
  const Eigen::Matrix2d Mm = sm.metric();
  const bool pole_edge = pole_pair(a, b);
  const Vec2 perp(-e.y(), e.x());

  // Ideal point in uv: equilateral in the metric, side s (unit, bounded by the edge's length).
  const double L = pole_edge ? 0.0 : std::sqrt(e.dot(Mm * e));
  const double s = pole_edge ? 1.0 : std::min(std::max(1.0, 0.55 * L), 2.0 * L);
  const double height = pole_edge ? 1.0 : std::sqrt(std::max(s * s - 0.25 * L * L, 0.05 * s * s));
  Vec2 d = pole_edge ? perp : Vec2(Mm.inverse() * perp);
  const double dl = std::sqrt(std::max(d.dot(Mm * d), 1e-300));
  d /= dl;
  Candidate ideal;
  ideal.uv = m + height * d;
  if (pole_edge) ideal.uv = off_pole(m, sm, perp, ideal.uv);
  bool ideal_ok = std::isfinite(ideal.uv.x()) && std::isfinite(ideal.uv.y());
  try {  // the ideal point may fall outside the surface's parameter range
    if (ideal_ok) ideal.s = fs_.eval(ideal.uv);
  } catch (const EvaluationError&) {
    ideal_ok = false;
  }
  const Eigen::Matrix2d Mp = ideal_ok ? ideal.s.metric() : Mm;
  // Ranking metric: the midpoint's, except on a pole where it is singular.
  const Eigen::Matrix2d M = pole_edge ? Mp : Mm;

  // Nearby front: a box holding the metric ball of radius lv.radius * s around the ideal point.
  const double r = lv.radius * s;
  const Eigen::Matrix2d Minv = M.inverse();
  Vec2 half(r * std::sqrt(std::max(Minv(0, 0), 0.0)), r * std::sqrt(std::max(Minv(1, 1), 0.0)));
  const Vec2 span = hi_ - lo_;
  half = half.cwiseMin(span);
  Vec2 blo = ideal.uv - half, bhi = ideal.uv + half;
  blo = blo.cwiseMin(ua).cwiseMin(ub);
  bhi = bhi.cwiseMax(ua).cwiseMax(ub);
  if (!std::isfinite(blo.x()) || !std::isfinite(blo.y()) || !std::isfinite(bhi.x()) ||
      !std::isfinite(bhi.y())) {
    blo = lo_;
    bhi = hi_;
  }
  gather(blo, bhi);
  // New points: the uv ideal point, and when it is poor the one placed in space.
  const double new_rank = 0.55;
  const double q_ideal = ideal_ok ? check(a, b, ideal, lv) : -1;
  Candidate c3;
  bool have_3d = false;
  if (!pole_edge && q_ideal < 0.6 && ideal_in_space(a, b, m, sm, s, ideal_ok ? ideal.uv : m, c3)) {
    have_3d = true;
    c3.in_space = true;
    c3.rank = new_rank + (q_ideal >= 0 ? 1e-9 : -1e-9);
    if (c3.uv.x() < blo.x() || c3.uv.y() < blo.y() || c3.uv.x() > bhi.x() || c3.uv.y() > bhi.y())
      gather(blo.cwiseMin(c3.uv), bhi.cwiseMax(c3.uv));
  }

  std::vector<Candidate> cands;
  // Front neighbours of the edge are always candidates (they close loops).
  int prev = -1, next = -1;
  for (int ej : near_edges_) {
    if (edges_[ej].a == b) next = edges_[ej].b;
    if (edges_[ej].b == a) prev = edges_[ej].a;
  }
  for (int k : near_nodes_) {
    if (k == a || k == b) continue;
    if (orient(ua, ub, fm_.uv[k]) <= 0) continue;
    const Vec2 dk = fm_.uv[k] - ideal.uv;
    const double dist = std::sqrt(std::max(dk.dot(M * dk), 0.0)) / s;
    if (dist > lv.radius && k != prev && k != next) continue;
    Candidate c;
    c.node = k;
    c.uv = fm_.uv[k];
    c.s = fm_.s[k];
    c.rank = dist;
    cands.push_back(c);
  }
  if (ideal_ok && clear_of_front(ideal.uv, M, lv.near_new * s)) {
    ideal.rank = new_rank;
    cands.push_back(ideal);
  }
  if (have_3d && clear_of_front(c3.uv, M, lv.near_new * s)) cands.push_back(c3);
  std::stable_sort(cands.begin(), cands.end(),
                   [](const Candidate& x, const Candidate& y) { return x.rank < y.rank; });

  int best = -1;
  double best_q = -1;
  for (size_t i = 0; i < cands.size(); ++i) {
    const bool is_ideal = cands[i].node < 0 && !cands[i].in_space;
    const double q = is_ideal ? q_ideal : check(a, b, cands[i], lv);
    if (q < 0) continue;
    if (q >= lv.q_min) {
      best = static_cast<int>(i);
      best_q = q;
      break;
    }
    if (lv.take_best && q > best_q) {
      best_q = q;
      best = static_cast<int>(i);
    }
  }
  if (best < 0) return false;
  if (best_q < lv.q_min && !lv.take_best) return false;
  Candidate& c = cands[best];
  int cn = c.node;
  if (cn < 0) {
    cn = fm_.add_node(c.uv, c.s, -1);
    if (c.in_space) ++fronts_3d_;
  }
  fm_.tris.push_back({a, b, cn});
  count_uses(a, b);
  count_uses(b, cn);
  count_uses(cn, a);
  kill_edge(ei);
  const int ca = find_edge(cn, a);
  if (ca >= 0) kill_edge(ca); else add_edge(a, cn);
  const int bc = find_edge(b, cn);
  if (bc >= 0) kill_edge(bc); else add_edge(cn, b);
  return true;
}

Vec2 Front::off_pole(const Vec2& m, const SurfaceSample& pole, const Vec2& perp, const Vec2& fallback) {
  const double reach = (hi_ - lo_).norm();
  if (!(perp.norm() > 0) || !(reach > 0)) return fallback;
  const Vec2 dir = perp.normalized();
  // Distance from the pole at uv m + t dir, in sizes wanted there.
  auto sizes_away = [&](double t) {
    const SurfaceSample q = fs_.eval(m + t * dir);
    return (q.p - pole.p).norm() / q.h;
  };
  try {
    // A bracket [lo, hi] from a thousandth of the face's uv span, halved
    // or doubled, then halved to a hundredth of its length.
    double lo = 0, hi = 1e-3 * reach;
    if (sizes_away(hi) >= 1) {
      for (int it = 0; it < 60 && lo == 0; ++it) {
        if (sizes_away(0.5 * hi) < 1) lo = 0.5 * hi;
        else hi *= 0.5;
      }
    } else {
      while (sizes_away(hi) < 1) {
        if (hi >= reach) return fallback;
        lo = hi;
        hi = std::min(2 * hi, reach);
      }
    }
    for (int it = 0; it < 20 && hi - lo > 0.01 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (sizes_away(mid) < 1 ? lo : hi) = mid;
    }
    return m + hi * dir;
  } catch (const EvaluationError&) {
    return fallback;
  }
}

bool Front::ideal_in_space(int a, int b, const Vec2& m, const SurfaceSample& sm, double s, const Vec2& guess,
                           Candidate& out) {
  const Vec3& pa = fm_.s[a].p;
  const Vec3& pb = fm_.s[b].p;
  const Vec3 ab = pb - pa;
  if (sm.n.norm() == 0 || ab.norm() == 0) return false;
  Vec3 t = sm.n.cross(ab);
  if (t.norm() == 0) return false;
  t.normalize();
  const double side = s * sm.h;
  const double height = std::sqrt(std::max(side * side - 0.25 * ab.squaredNorm(), 0.05 * side * side));
  const Vec3 target = 0.5 * (pa + pb) + height * t;
  Vec2 uv = std::isfinite(guess.x()) && std::isfinite(guess.y()) ? guess : m;
  try {
    if (!fs_.project(target, uv)) return false;
    out.uv = uv;
    out.s = fs_.eval(uv);
  } catch (const EvaluationError&) {
    return false;
  }
  out.node = -1;
  return (out.s.p - target).norm() <= 0.5 * height;
}

}  // namespace sizemesh::detail
