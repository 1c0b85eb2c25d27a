#include "mesher/face_surface.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace sizemesh {
namespace {

// Unit du x dv, zero where the surface is singular (a pole, a stalled edge).
Vec3 unit_normal(const SurfaceD1& d) {
  const Vec3 n = d.du.cross(d.dv);
  const double len = n.norm();
  return len > 1e-9 * (d.du.squaredNorm() + d.dv.squaredNorm()) && len > 0 ? Vec3(n / len) : Vec3(Vec3::Zero());
}

// Depth, in the surface's uv, of the band along one side of the box (axis 0:
// a side u = const; `high`: the side at the upper bound) across which the
// surface stays on the side's own curve in space; 0 where it moves at once.
// Found by bisection on the largest move of points spread along the side.
double band_depth(const Geometry& g, int face, const UVBox& box, int axis, bool high) {
  constexpr int kSamples = 17;
  const int other = 1 - axis;
  const double range = box.hi[axis] - box.lo[axis], side = high ? box.hi[axis] : box.lo[axis];
  if (!(range > 0) || !std::isfinite(range)) return 0;
  std::array<Vec2, kSamples> at;
  std::array<Vec3, kSamples> p;
  double along = 0;  // length of the side's curve in space
  try {
    for (int k = 0; k < kSamples; ++k) {
      at[k][axis] = side;
      at[k][other] = box.lo[other] + (box.hi[other] - box.lo[other]) * k / (kSamples - 1);
      p[k] = g.eval_face(face, at[k]).p;
      if (k > 0) along += (p[k] - p[k - 1]).norm();
    }
  } catch (const EvaluationError&) {
    return 0;
  }
  // A pole (the side one point) has no band: it moves at once across.
  const double still = 1e-9 * along;
  if (!(still > 0) || !std::isfinite(still)) return 0;
  auto moves = [&](double depth) {
    try {
      for (int k = 0; k < kSamples; ++k) {
        Vec2 uv = at[k];
        uv[axis] += high ? -depth : depth;
        if (!((g.eval_face(face, uv).p - p[k]).norm() <= still)) return true;
      }
      return false;
    } catch (const EvaluationError&) {
      return true;
    }
  };
  double lo = 1e-4 * range, hi = 0.5 * range;
  if (moves(lo) || !moves(hi)) return 0;
  for (int i = 0; i < 60 && hi - lo > 1e-12 * range; ++i) (moves(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
  return hi;
}

}  // namespace

FaceSurface::FaceSurface(const Geometry& g, const SizeField& h, int face)
    : g_(g),
      h_(h),
      face_(face),
      period_u_(g.face_period_u(face)),
      period_v_(g.face_period_v(face)),
      fallback_h_(std::max(g.face_boundary_length(face) / 12, 1e-300)),
      stretch_(g, face) {
  box_ = live_ = g.face_uv_bounds(face);
  const double period[2] = {period_u_, period_v_};
  const UVBox& box = box_;
  for (int axis = 0; axis < 2; ++axis) {
    if (period[axis] > 0) continue;
    const double lo = band_depth(g, face, box, axis, false), hi = band_depth(g, face, box, axis, true);
    if (lo + hi >= box.hi[axis] - box.lo[axis]) continue;
    live_.lo[axis] += lo;
    live_.hi[axis] -= hi;
    banded_ = banded_ || lo > 0 || hi > 0;
  }
}

Vec2 FaceSurface::off_band(const Vec2& uv) const {
  if (!banded_) return uv;
  const Vec2 su = to_surface(uv);
  Vec2 in = su;
  for (int axis = 0; axis < 2; ++axis) {
    const UVBox& box = box_;
    // Only inside a band: beyond the box (a pcurve past its bounds) stays.
    if (su[axis] < live_.lo[axis] && su[axis] >= box.lo[axis] - 1e-9 * (box.hi[axis] - box.lo[axis]))
      in[axis] = live_.lo[axis];
    if (su[axis] > live_.hi[axis] && su[axis] <= box.hi[axis] + 1e-9 * (box.hi[axis] - box.lo[axis]))
      in[axis] = live_.hi[axis];
  }
  return in == su ? uv : to_mesher(in);
}

bool FaceSurface::turned_at_centroid(const Vec2& ua, const Vec2& ub, const Vec2& uc, const Vec3& nt) const {
  try {
    // At the centroid in the surface's uv, as the quality report takes it.
    const Vec2 c = (to_surface(ua) + to_surface(ub) + to_surface(uc)) / 3.0;
    const Vec3 nc = unit_normal(g_.eval_face(face_, c));
    return nc.squaredNorm() > 0 && !(nt.dot(nc) > 0);
  } catch (const EvaluationError&) {
    return true;
  }
}

SurfaceSample FaceSurface::eval_shape(const Vec2& uv) const {
  const SurfaceD1 d = g_.eval_face(face_, stretch_.to_surface(uv));
  const Vec2 slope = stretch_.slope(uv);
  SurfaceSample s;
  s.p = d.p;
  s.du = d.du * slope.x();
  s.dv = d.dv * slope.y();
  s.n = unit_normal(d);
  return s;
}

SurfaceSample FaceSurface::eval(const Vec2& uv) {
  SurfaceSample s = eval_shape(uv);
  s.h = h_.at(face_, stretch_.to_surface(uv), hint_);
  ++size_queries;
  if (!(s.h > 0) || !std::isfinite(s.h)) s.h = fallback_h_;  // a size map with a hole
  return s;
}

Vec2 FaceSurface::unwrap(Vec2 uv, const Vec2& near) const {
  if (period_u_ > 0) uv.x() -= period_u_ * std::round((uv.x() - near.x()) / period_u_);
  if (period_v_ > 0) uv.y() -= period_v_ * std::round((uv.y() - near.y()) / period_v_);
  return uv;
}

bool FaceSurface::project(const Vec3& xyz, Vec2& uv) const {
  const Vec2 start = uv;
  Vec2 su = stretch_.to_surface(uv);
  if (!g_.project_to_face(face_, xyz, su)) return false;
  if (!std::isfinite(su.x()) || !std::isfinite(su.y())) return false;
  uv = off_band(unwrap(stretch_.to_mesher(su), start));  // periodic directions are never stretched
  return true;
}

}  // namespace sizemesh
