#include "mesher/face_surface.h"

#include <algorithm>
#include <cmath>

namespace sizemesh {
namespace {

// Unit du x dv, zero where the surface is singular (a pole, a stalled edge).
Vec3 unit_normal(const SurfaceD1& d) {
  const Vec3 n = d.du.cross(d.dv);
  const double len = n.norm();
  return len > 1e-9 * (d.du.squaredNorm() + d.dv.squaredNorm()) && len > 0 ? Vec3(n / len) : Vec3(Vec3::Zero());
}

}  // namespace

FaceSurface::FaceSurface(const Geometry& g, const SizeFunction& h, int face)
    : g_(g),
      h_(h),
      face_(face),
      period_u_(g.face_period_u(face)),
      period_v_(g.face_period_v(face)),
      fallback_h_(std::max(g.face_boundary_length(face) / 12, 1e-300)),
      stretch_(g, face) {}

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
  uv = unwrap(stretch_.to_mesher(su), start);  // periodic directions are never stretched
  return true;
}

}  // namespace sizemesh
