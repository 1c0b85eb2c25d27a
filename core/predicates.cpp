#include "core/predicates.h"

#include <boost/multiprecision/cpp_int.hpp>

#include <algorithm>
#include <climits>
#include <cmath>

namespace sizemesh {

namespace {

// Exact fallback: every double is an integer times a power of two, so scaled
// by the smallest power among the inputs all of them become integers and the
// determinant is an integer polynomial. Fixed 1024-bit integers (no allocation)
// hold it when the inputs span less than 2^250; rationals otherwise.
using Int = boost::multiprecision::number<boost::multiprecision::cpp_int_backend<
    1024, 1024, boost::multiprecision::signed_magnitude, boost::multiprecision::unchecked, void>>;
using Rational = boost::multiprecision::cpp_rational;

constexpr double kEps = 1.1102230246251565e-16;  // 2^-53, unit round-off

template <class T>
int sign_of(const T& x) {
  return x > 0 ? 1 : (x < 0 ? -1 : 0);
}

// Exponent of the lowest bit of v's 53-bit significand (none for 0).
int low_exponent(double v) {
  int e;
  std::frexp(v, &e);
  return e - 53;
}

// The n values as integers v * 2^-low, with low the least low_exponent; false
// when the span is too wide for Int.
template <size_t N>
bool as_integers(const std::array<double, N>& v, std::array<Int, N>& out) {
  int lo = INT32_MAX, hi = INT32_MIN;
  for (double x : v)
    if (x != 0) {
      lo = std::min(lo, low_exponent(x));
      hi = std::max(hi, low_exponent(x));
    }
  if (lo == INT32_MAX) lo = hi = 0;
  if (hi - lo > 250) return false;
  for (size_t i = 0; i < N; ++i) {
    if (v[i] == 0) {
      out[i] = 0;
      continue;
    }
    const int e = low_exponent(v[i]);
    const auto m = static_cast<long long>(std::ldexp(v[i], -e));  // the significand, exact
    out[i] = Int(m) << (e - lo);
  }
  return true;
}

// det [a-d; b-d; c-d] of any exact number type, from the 12 coordinates.
template <class T, class Array>
int orient3d_exact(const Array& r) {
  T e[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) e[i][k] = T(r[3 * i + k]) - T(r[9 + k]);
  const T x = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) + e[1][0] * (e[2][1] * e[0][2] - e[2][2] * e[0][1]) +
              e[2][0] * (e[0][1] * e[1][2] - e[0][2] * e[1][1]);
  return sign_of(x);
}

}  // namespace

// Filter after Shewchuk (1997): the rounded determinant is trusted when it
// exceeds (7 + 56 eps) eps times the permanent; otherwise it is recomputed
// exactly (scaled integers, or rationals for inputs of very wide range).
int orient3d_sign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 ad = a - d, bd = b - d, cd = c - d;
  const double m1 = bd.y() * cd.z(), m2 = bd.z() * cd.y();
  const double m3 = cd.y() * ad.z(), m4 = cd.z() * ad.y();
  const double m5 = ad.y() * bd.z(), m6 = ad.z() * bd.y();
  const double det = ad.x() * (m1 - m2) + bd.x() * (m3 - m4) + cd.x() * (m5 - m6);
  const double permanent = (std::abs(m1) + std::abs(m2)) * std::abs(ad.x()) +
                           (std::abs(m3) + std::abs(m4)) * std::abs(bd.x()) +
                           (std::abs(m5) + std::abs(m6)) * std::abs(cd.x());
  const double bound = (7.0 + 56.0 * kEps) * kEps * permanent;
  if (det > bound) return 1;
  if (det < -bound) return -1;
  const std::array<double, 12> v = {a.x(), a.y(), a.z(), b.x(), b.y(), b.z(),
                                    c.x(), c.y(), c.z(), d.x(), d.y(), d.z()};
  std::array<Int, 12> n;
  if (as_integers(v, n)) return orient3d_exact<Int>(n);
  return orient3d_exact<Rational>(v);
}

// Same filter for the 2D determinant, bound (3 + 16 eps) eps times the permanent.
int orient2d_sign(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double l = (b.x() - a.x()) * (c.y() - a.y()), r = (b.y() - a.y()) * (c.x() - a.x());
  const double det = l - r, bound = (3.0 + 16.0 * kEps) * kEps * (std::abs(l) + std::abs(r));
  if (det > bound) return 1;
  if (det < -bound) return -1;
  const std::array<double, 6> v = {a.x(), a.y(), b.x(), b.y(), c.x(), c.y()};
  std::array<Int, 6> n;
  if (as_integers(v, n)) return sign_of((n[2] - n[0]) * (n[5] - n[1]) - (n[3] - n[1]) * (n[4] - n[0]));
  const Rational ax(a.x()), ay(a.y()), bx(b.x()), by(b.y()), cx(c.x()), cy(c.y());
  return sign_of((bx - ax) * (cy - ay) - (by - ay) * (cx - ax));
}

namespace {

// Closed uv segments ab and cd touch (exact).
bool segments_touch_exact(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const int o1 = orient2d_sign(a, b, c), o2 = orient2d_sign(a, b, d);
  const int o3 = orient2d_sign(c, d, a), o4 = orient2d_sign(c, d, b);
  if (o1 == 0 && o2 == 0) {  // collinear: the boxes of the segments overlap
    for (int k = 0; k < 2; ++k)
      if (std::max(a[k], b[k]) < std::min(c[k], d[k]) || std::max(c[k], d[k]) < std::min(a[k], b[k])) return false;
    return true;
  }
  return o1 * o2 <= 0 && o3 * o4 <= 0;
}

}  // namespace

bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const int dp = orient3d_sign(a, b, c, p), dq = orient3d_sign(a, b, c, q);
  if (dp * dq > 0) return false;
  if (dp == 0 && dq == 0) {
    const DominantProjection flat(a, b, c);
    const Vec2 P = flat(p), Q = flat(q), A = flat(a), B = flat(b), C = flat(c);
    if (segments_touch_exact(P, Q, A, B) || segments_touch_exact(P, Q, B, C) || segments_touch_exact(P, Q, C, A))
      return true;
    const int o1 = orient2d_sign(A, B, P), o2 = orient2d_sign(B, C, P), o3 = orient2d_sign(C, A, P);
    return (o1 >= 0 && o2 >= 0 && o3 >= 0) || (o1 <= 0 && o2 <= 0 && o3 <= 0);  // p inside
  }
  const int s1 = orient3d_sign(p, q, a, b), s2 = orient3d_sign(p, q, b, c), s3 = orient3d_sign(p, q, c, a);
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

bool triangles_meet(const std::array<Vec3, 3>& s, const std::array<Vec3, 3>& t) {
  for (int k = 0; k < 3; ++k) {
    if (segment_meets_triangle(s[k], s[(k + 1) % 3], t[0], t[1], t[2])) return true;
    if (segment_meets_triangle(t[k], t[(k + 1) % 3], s[0], s[1], s[2])) return true;
  }
  return false;
}

}  // namespace sizemesh
