// Whether a candidate triangle may join the advancing front (front.h): in uv
// counter-clockwise, within the front's open angles, crossing no front edge
// and holding no front node; in space facing the surface normal at its
// corners and centroid, with a good shape and no sliver left beside it.
#include "mesher/front.h"

#include <algorithm>
#include <cmath>

#include "core/predicates.h"

namespace sizemesh::detail {
namespace {

// Counter-clockwise angle from direction u to direction v, in [0, 2 pi).
double ccw_angle(const Vec2& u, const Vec2& v) {
  const double t = std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
  return t < 0 ? t + 2 * kPi : t;
}

// Point x within a small fraction of the segment's length of segment pq (space).
bool near_segment(const Vec3& p, const Vec3& q, const Vec3& x) {
  const Vec3 d = q - p;
  const double l2 = d.squaredNorm();
  if (!(l2 > 0)) return false;
  const double t = (x - p).dot(d) / l2;
  if (t <= 0.02 || t >= 0.98) return false;
  return (x - p - t * d).squaredNorm() < 0.03 * 0.03 * l2;
}

}  // namespace

double Front::check(int a, int b, const Candidate& c, const Level& lv) {
  const Vec2& ua = fm_.uv[a];
  const Vec2& ub = fm_.uv[b];
  const Vec2& uc = c.uv;
  // A front neighbour taken as apex may lie outside the gathered box: the
  // front its new edges could cross is gathered first.
  if ((uc.array() < box_lo_.array()).any() || (uc.array() > box_hi_.array()).any())
    gather(box_lo_.cwiseMin(uc), box_hi_.cwiseMax(uc));
  const double o = orient(ua, ub, uc);
  const double scale = (ub - ua).norm() * ((uc - ua).norm() + (uc - ub).norm());
  if (!(o > 1e-10 * scale)) return kFoldedInUv;
  // Seam copies: no triangle joins two uv images of one node, and no inner
  // edge repeats a boundary edge in space (it would be non-manifold).
  if (c.node >= 0 && fm_.global[c.node] >= 0) {
    const int gc = fm_.global[c.node];
    if ((gc == fm_.global[a] && !pole_pair(a, c.node)) || (gc == fm_.global[b] && !pole_pair(b, c.node)))
      return kNonManifold;
  }
  // The triangle lies in the unmeshed region at each of its corners: an edge
  // leaving a front node outside the node's open angle crosses no front edge
  // yet escapes through the node (into the meshed part or out of the domain).
  if (!within_open_angle(a, ub, uc) || !within_open_angle(b, uc, ua) ||
      (c.node >= 0 && !within_open_angle(c.node, ua, ub)))
    return kOutsideOpenAngle;
  work_ += static_cast<long long>(near_edges_.size() + near_nodes_.size());
  // New edges must cross no front edge.
  const bool new_ac = c.node < 0 || find_edge(c.node, a) < 0;
  const bool new_cb = c.node < 0 || find_edge(b, c.node) < 0;
  if (c.node >= 0 && ((new_ac && used_in_space(a, c.node)) || (new_cb && used_in_space(c.node, b))))
    return kNonManifold;
  for (int ei : near_edges_) {
    const FrontEdge& e = edges_[ei];
    if (!e.alive) continue;
    const Vec2& p = fm_.uv[e.a];
    const Vec2& q = fm_.uv[e.b];
    if (new_ac && e.a != a && e.b != a && e.a != c.node && e.b != c.node &&
        segments_meet(ua, uc, p, q))
      return kCrossesFront;
    if (new_cb && e.a != b && e.b != b && e.a != c.node && e.b != c.node &&
        segments_meet(uc, ub, p, q))
      return kCrossesFront;
  }
  // No front node inside or on the triangle.
  const double tol = -1e-10 * o;
  for (int k : near_nodes_) {
    if (k == a || k == b || k == c.node) continue;
    const Vec2& uk = fm_.uv[k];
    if (orient(ua, ub, uk) >= tol && orient(ub, uc, uk) >= tol && orient(uc, ua, uk) >= tol)
      return kHoldsFrontNode;
    // Nor (in space) just beside a new edge: it would leave a sliver for later.
    if (lv.cos_min > -1 && !fm_.pole[k] && ((new_ac && near_segment(fm_.s[a].p, c.s.p, fm_.s[k].p)) ||
                         (new_cb && near_segment(c.s.p, fm_.s[b].p, fm_.s[k].p))))
      return kSliverLeft;
  }
  // Space: the triangle faces the way of the surface normal (Tremel procedure 2).
  const bool pole_tri = pole_pair(a, b) || (c.node >= 0 && (pole_pair(b, c.node) || pole_pair(c.node, a)));
  if (pole_tri) return 0.8;
  const Vec3& pa = fm_.s[a].p;
  const Vec3& pb = fm_.s[b].p;
  const Vec3& pc = c.s.p;
  const Vec3 nt = (pb - pa).cross(pc - pa);
  const double lt = nt.norm();
  if (!(lt > 0)) return kZeroAreaInSpace;
  const Vec3* normals[3] = {&fm_.s[a].n, &fm_.s[b].n, &c.s.n};  // zero on poles
  for (const Vec3* n : normals)
    if (n->squaredNorm() > 0 && nt.dot(*n) <= lv.cos_min * lt) return kTurnedAtCorner;
  const double q = triangle_quality(pa, pb, pc);
  if (!(q > 1e-6)) return kPoorShape;
  // And at the uv centroid, where a curved surface may turn away between
  // corners: never against the normal there (the quality report's test for
  // an inverted triangle), but in a lenient run's loosest levels.
  if (lv.cos_min > -1 || !may_turn_) {
    Vec3 nc;
    try {
      nc = fs_.eval_shape((ua + ub + uc) / 3.0).n;
    } catch (const EvaluationError&) {
      return kTurnedAtCentroid;
    }
    if (nc.squaredNorm() > 0 && nt.dot(nc) <= std::max(lv.cos_min, 0.0) * lt) return kTurnedAtCentroid;
  }
  return q;
}

bool Front::within_open_angle(int k, const Vec2& x, const Vec2& y) const {
  const Vec2& uk = fm_.uv[k];
  const Vec2 dx = x - uk, dy = y - uk;
  constexpr double eps = 1e-9;  // collinear directions (closing a loop) pass
  bool touched = false;
  for (int eo : near_edges_) {
    if (!edges_[eo].alive || edges_[eo].a != k) continue;
    const Vec2 dn = fm_.uv[edges_[eo].b] - uk;
    for (int ei : near_edges_) {
      if (!edges_[ei].alive || edges_[ei].b != k) continue;
      touched = true;
      const double open = ccw_angle(dn, fm_.uv[edges_[ei].a] - uk);
      const double ax = ccw_angle(dn, dx), ay = ccw_angle(dn, dy);
      const double ax0 = ax > 2 * kPi - eps ? 0.0 : ax;  // along k->n
      if (ax0 <= ay + eps && ay <= open + eps) return true;
    }
  }
  return !touched;  // no front edges seen at k: nothing to test against
}

bool Front::clear_of_front(const Vec2& p, const Eigen::Matrix2d& M, double min_dist) const {
  const double d2 = min_dist * min_dist;
  for (int k : near_nodes_) {
    const Vec2 d = fm_.uv[k] - p;
    if (d.dot(M * d) < d2) return false;
  }
  for (int ei : near_edges_) {
    const FrontEdge& e = edges_[ei];
    if (!e.alive) continue;
    const Vec2& q0 = fm_.uv[e.a];
    const Vec2 dq = fm_.uv[e.b] - q0;
    const double l2 = dq.dot(M * dq);
    double t = l2 > 0 ? (p - q0).dot(M * dq) / l2 : 0;
    t = std::clamp(t, 0.0, 1.0);
    const Vec2 d = q0 + t * dq - p;
    if (d.dot(M * d) < 0.49 * d2) return false;
  }
  return true;
}

}  // namespace sizemesh::detail
