// One rectangular face with a strongly distorted parametrisation, built analytically, for the mesher's tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/geometry.h"

namespace sizemesh::test {

// One rectangular face [0, L] x [0, W] (z = 0) with a strongly distorted
// parametrisation, built analytically: S(u, v) = (x(u), y(v), 0) with
// x(u) = L (0.05 u + 0.95 u^3) and y(v) = W (0.1 v + 0.9 v^2).
// Points 1..4 at the corners, curves 1..4 the sides (t in [0, 1]).
class DistortedRectangle final : public Geometry {
 public:
  // stalls: x(u) = L (2u - u^2), whose speed falls to zero at u = 1 (a
  // trailing edge or tip closed by coincident control points), and the face
  // sheared by y += shear x (u-lines running obliquely into that edge).
  DistortedRectangle(double L, double W, bool stalls = false, double shear = 0)
      : L_(L), W_(W), stalls_(stalls), shear_(shear) {}
  int num_faces() const override { return 1; }
  int num_curves() const override { return 4; }
  int num_points() const override { return 4; }
  SurfaceD1 eval_face(int, const Vec2& uv) const override {
    return {Vec3(x(uv.x()), y(uv.y()) + shear_ * x(uv.x()), 0), Vec3(dx(uv.x()), shear_ * dx(uv.x()), 0),
            Vec3(0, dy(uv.y()), 0)};
  }
  bool principal_curvatures(int, const Vec2&, double& k1, double& k2) const override {
    k1 = k2 = 0;
    return true;
  }
  bool face_reversed(int) const override { return false; }
  UVBox face_uv_bounds(int) const override { return {Vec2(0, 0), Vec2(1, 1)}; }
  double face_period_u(int) const override { return 0; }
  double face_period_v(int) const override { return 0; }
  double face_area(int) const override { return L_ * W_; }
  double face_boundary_length(int) const override { return 2 * (L_ * std::hypot(1.0, shear_) + W_); }
  std::vector<FaceLoop> face_loops(int) const override {
    return {{{1, false, 0}, {2, false, 0}, {3, false, 0}, {4, false, 0}}};
  }
  bool project_to_face(int, const Vec3& p, Vec2& uv) const override {
    for (int it = 0; it < 50; ++it) {
      uv.x() = std::clamp(uv.x() - (x(uv.x()) - p.x()) / std::max(dx(uv.x()), 1e-3 * L_), 0.0, 1.0);
      uv.y() -= (y(uv.y()) + shear_ * x(uv.x()) - p.y()) / dy(uv.y());
    }
    return true;
  }
  void curve_range(int, double& t0, double& t1) const override {
    t0 = 0;
    t1 = 1;
  }
  bool curve_degenerated(int) const override { return false; }
  Vec3 eval_curve(int c, double t) const override { return eval_face(1, pcurve(c, t)).p; }
  Vec3 curve_tangent(int c, double t) const override {
    const SurfaceD1 s = eval_face(1, pcurve(c, t));
    const Vec2 d = pcurve(c, 1) - pcurve(c, 0);
    return s.du * d.x() + s.dv * d.y();
  }
  bool curve_curvature(int, double, double& k) const override {
    k = 0;
    return true;
  }
  double curve_length(int c) const override { return (eval_curve(c, 1) - eval_curve(c, 0)).norm(); }
  int curve_start_point(int c) const override { return c; }
  int curve_end_point(int c) const override { return c % 4 + 1; }
  Vec2 eval_pcurve(int c, int, int, double t) const override { return pcurve(c, t); }
  Vec3 point_xyz(int p) const override { return eval_face(1, corner(p)).p; }

 private:
  static Vec2 corner(int p) {
    const Vec2 c[4] = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
    return c[p - 1];
  }
  static Vec2 pcurve(int c, double t) { return corner(c) + t * (corner(c % 4 + 1) - corner(c)); }
  double x(double u) const { return stalls_ ? L_ * (2 * u - u * u) : L_ * (0.05 * u + 0.95 * u * u * u); }
  double dx(double u) const { return stalls_ ? L_ * (2 - 2 * u) : L_ * (0.05 + 2.85 * u * u); }
  double y(double v) const { return W_ * (0.1 * v + 0.9 * v * v); }
  double dy(double v) const { return W_ * (0.1 + 1.8 * v); }
  double L_, W_;
  bool stalls_;
  double shear_;
};

}  // namespace sizemesh::test
