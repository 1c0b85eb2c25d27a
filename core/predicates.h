// Geometric predicates and small measures, in one place for every stage:
// uv orientation and segment tests (face mesher, size query), triangle shape
// measures (optimiser, quality report) in floating point, and the exact 3D
// triangle intersection tests of the self-intersection check (predicates.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "core/types.h"

namespace sizemesh {

// Twice the signed area of (a, b, c) in uv; > 0 counter-clockwise.
inline double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Shape quality 4 sqrt(3) area / sum of squared edge lengths (1 equilateral, 0 flat).
inline double triangle_quality(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double l = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  if (!(l > 0)) return 0;
  return 2.0 * std::sqrt(3.0) * (b - a).cross(c - a).norm() / l;
}

// Interior angles of a space triangle at a, b, c (degrees; 0 at a corner
// with a zero-length edge).
inline std::array<double, 3> corner_angles_deg(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 p[3] = {a, b, c};
  std::array<double, 3> angle{};
  for (int k = 0; k < 3; ++k) {
    const Vec3 u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
    angle[k] = std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / kPi;
  }
  return angle;
}

// A sliver: a triangle whose smallest angle is under kSliverDeg degrees (the
// quality bar the report counts by). A triangle across a strip narrower than
// kSliverTan (tan of that angle) times its edge length is one, whatever its shape.
constexpr double kSliverDeg = 12.0;
constexpr double kSliverTan = 0.21255656167002213;
constexpr double kSliverCos = 0.97814760073380569;  // cos of kSliverDeg

// Smallest interior angle of a space triangle (degrees; 0 with a zero-length edge).
// The smallest angle lies opposite the shortest edge: only the corners facing
// edges within 1e-8 of the shortest are measured, the same values as
// corner_angles_deg gives there; all three where that angle is under 0.01
// degrees (the cross product of nearly parallel edges loses digits there, so
// the order of the computed angles may differ from that of the edges).
inline double min_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 p[3] = {a, b, c};
  double l[3];
  for (int k = 0; k < 3; ++k) l[k] = (p[(k + 2) % 3] - p[(k + 1) % 3]).squaredNorm();  // opposite corner k
  if (!(std::sqrt(l[0]) > 0 && std::sqrt(l[1]) > 0 && std::sqrt(l[2]) > 0)) return 0;
  const double shortest = std::min({l[0], l[1], l[2]});
  double best = 180.0;
  for (int k = 0; k < 3; ++k) {
    if (!(l[k] <= shortest * (1 + 1e-8))) continue;
    const Vec3 u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
    best = std::min(best, std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / kPi);
  }
  if (best < 0.01) {
    const auto angle = corner_angles_deg(a, b, c);
    return std::min({180.0, angle[0], angle[1], angle[2]});
  }
  return best;
}

// A triangle of zero area: twice its area is not above 1e-12 of its summed
// squared edge lengths (the quality report's and the intersection check's test).
inline bool zero_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double l2 = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  return !((b - a).cross(c - a).norm() > 1e-12 * l2);
}

// The projection to uv that drops the dominant axis of the normal of triangle
// (a, b, c): a non-degenerate triangle stays non-degenerate, and only its own
// points project onto it.
struct DominantProjection {
  int axis = 0;
  DominantProjection(const Vec3& a, const Vec3& b, const Vec3& c) {
    (b - a).cross(c - a).cwiseAbs().maxCoeff(&axis);
  }
  Vec2 operator()(const Vec3& x) const { return Vec2(x[(axis + 1) % 3], x[(axis + 2) % 3]); }
};

// True when uv segments p1p2 and q1q2 cross or touch (collinear overlap included).
inline bool segments_meet(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
  const double lp = (p2 - p1).norm(), lq = (q2 - q1).norm();
  const double tol = 1e-12 * (lp + lq) * (lp + lq);
  const double d1 = orient(q1, q2, p1), d2 = orient(q1, q2, p2);
  const double d3 = orient(p1, p2, q1), d4 = orient(p1, p2, q2);
  if (((d1 > tol && d2 < -tol) || (d1 < -tol && d2 > tol)) &&
      ((d3 > tol && d4 < -tol) || (d3 < -tol && d4 > tol)))
    return true;
  auto within = [](const Vec2& a, const Vec2& b, const Vec2& p) {
    return p.x() >= std::min(a.x(), b.x()) && p.x() <= std::max(a.x(), b.x()) &&
           p.y() >= std::min(a.y(), b.y()) && p.y() <= std::max(a.y(), b.y());
  };
  if (std::abs(d1) <= tol && within(q1, q2, p1)) return true;
  if (std::abs(d2) <= tol && within(q1, q2, p2)) return true;
  if (std::abs(d3) <= tol && within(p1, p2, q1)) return true;
  if (std::abs(d4) <= tol && within(p1, p2, q2)) return true;
  return false;
}

// True when closed uv segments ab and cd touch, without tolerance (touching counts).
inline bool segments_touch(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 == 0 && o2 == 0) {  // collinear: overlap of the projections
    const Vec2 u = b - a;
    const double t1 = (c - a).dot(u), t2 = (d - a).dot(u);
    return std::max(t1, t2) >= 0 && std::min(t1, t2) <= u.squaredNorm();
  }
  return ((o1 <= 0 && o2 >= 0) || (o1 >= 0 && o2 <= 0)) && ((o3 <= 0 && o4 >= 0) || (o3 >= 0 && o4 <= 0));
}

// Nearest point of segment PQ to p: parameter s in [0,1] and squared distance.
inline void project_segment(const Vec2& P, const Vec2& Q, const Vec2& p, double& s, double& d2) {
  const Vec2 d = Q - P;
  const double len2 = d.squaredNorm();
  s = len2 > 0 ? std::clamp((p - P).dot(d) / len2, 0.0, 1.0) : 0.0;
  d2 = (p - (P + s * d)).squaredNorm();
}

// Distance between closed uv segments ab and cd (0 when they touch).
inline double segment_distance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  if (segments_touch(a, b, c, d)) return 0;
  double s, d2, best = INFINITY;
  for (const auto& [P, Q, x] : {std::array<Vec2, 3>{a, b, c}, {a, b, d}, {c, d, a}, {c, d, b}}) {
    project_segment(P, Q, x, s, d2);
    best = std::min(best, d2);
  }
  return std::sqrt(best);
}

// Sign (-1, 0, 1) of six times the signed volume of (a, b, c, d): > 0 when d
// lies below the plane of a, b, c seen counter-clockwise from above. Exact: a
// floating-point filter, and exact integer (or rational) arithmetic when the
// filter cannot tell.
int orient3d_sign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// Sign of twice the signed area of uv points (a, b, c), exact as orient3d_sign.
int orient2d_sign(const Vec2& a, const Vec2& b, const Vec2& c);

// True when closed segment pq meets closed triangle abc (a non-degenerate
// triangle), decided exactly. Coplanar cases are decided in the projection that
// drops the dominant axis of the triangle's normal.
bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c);

// True when two closed triangles meet: then an edge of one meets the other
// (the ends of their common segment lie on edges; a contained triangle's
// edges lie inside the other).
bool triangles_meet(const std::array<Vec3, 3>& s, const std::array<Vec3, 3>& t);

}  // namespace sizemesh
