// Kernel-free view of a B-rep for sizing/ and mesher/ (no OpenCASCADE types).
//
// Ids are 1-based: faces, curves (B-rep edges) and points (B-rep vertices) in
// the order of TopExp::MapShapes on the loaded shape. Every method is safe to
// call from several threads at once.
#pragma once

#include <cmath>
#include <vector>

#include "core/types.h"

namespace sizemesh {

// Surface position and first derivatives at one uv.
struct SurfaceD1 {
  Vec3 p, du, dv;
};

// One use of a curve in a face's boundary loop.
struct CurveUse {
  int curve = 0;          // curve id
  bool reversed = false;  // traversed from t1 to t0 in the loop
  int side = 0;           // which pcurve on a seam (0 or 1); 0 elsewhere
};

// A closed boundary loop (B-rep wire) of a face; loops[0] is the outer one.
using FaceLoop = std::vector<CurveUse>;

struct UVBox {
  Vec2 lo, hi;
};

class Geometry {
 public:
  virtual ~Geometry() = default;

  // True when the faces bound volumes (no free curve), normals out of them.
  virtual bool closed() const { return false; }
  // Side of the surface the fluid is on: +1 along the normals (a body in
  // the flow), -1 against them (the model is the flow domain, its cavities
  // the bodies), 0 unknown (sheets, open models).
  virtual int fluid_side() const { return 0; }

  virtual int num_faces() const = 0;
  virtual int num_curves() const = 0;
  virtual int num_points() const = 0;

  // --- faces ---
  virtual SurfaceD1 eval_face(int face, const Vec2& uv) const = 0;
  // Surface evaluations (eval_face calls) so far, over all threads; read
  // it while no other thread evaluates. 0 where not counted.
  virtual long long surface_evaluations() const { return 0; }
  // Those made on the calling thread.
  virtual long long thread_surface_evaluations() const { return 0; }
  // Principal curvatures at uv (1/length, signed, |k1| >= |k2|); false where they are undefined.
  virtual bool principal_curvatures(int face, const Vec2& uv, double& k1, double& k2) const = 0;
  // Largest absolute principal curvature at uv; false where it is undefined.
  bool max_curvature(int face, const Vec2& uv, double& k) const {
    double k1, k2;
    if (!principal_curvatures(face, uv, k1, k2)) return false;
    k = std::abs(k1);
    return std::isfinite(k);
  }
  // True where the face's orientation in its shell flips the surface normal.
  virtual bool face_reversed(int face) const = 0;
  // A plane, cylinder, cone, sphere or torus in its natural parameters: a
  // metric that separates in u and v, so the mesher needs no stretch of its uv.
  virtual bool face_elementary(int face) const { return false; }
  virtual UVBox face_uv_bounds(int face) const = 0;
  // The distinct knots of the face's surface along u (direction 0) or v (1)
  // inside its uv bounds (more than 1e-9 of their range from either end):
  // where a B-spline's parametric speed may jump. Empty for any other surface.
  virtual std::vector<double> face_knots(int face, int direction) const { return {}; }
  // Period in u / v, 0 when not periodic.
  virtual double face_period_u(int face) const = 0;
  virtual double face_period_v(int face) const = 0;
  // Span in u / v after which the face meets itself across a seam: its
  // period, or on a surface closed without one (a wing skin wrapped round
  // to its trailing edge, both ends one edge) the span of its parameter
  // range, beyond which eval_face() wraps; 0 when it does not wrap.
  virtual double face_wrap_u(int face) const { return face_period_u(face); }
  virtual double face_wrap_v(int face) const { return face_period_v(face); }
  virtual double face_area(int face) const = 0;            // exact (BRepGProp)
  virtual double face_boundary_length(int face) const = 0; // total wire length
  virtual std::vector<FaceLoop> face_loops(int face) const = 0;
  // Closest point on the face's surface to xyz, starting from uv; false if it fails.
  virtual bool project_to_face(int face, const Vec3& xyz, Vec2& uv) const = 0;
  // The nearest point of the whole face's parameter box, wherever uv starts:
  // slower, for a start that may lie where Newton stalls (a strip of the
  // surface collapsed onto a line, a pole). By default, project_to_face().
  virtual bool nearest_on_face(int face, const Vec3& xyz, Vec2& uv) const { return project_to_face(face, xyz, uv); }

  // --- curves ---
  virtual void curve_range(int curve, double& t0, double& t1) const = 0;
  virtual bool curve_degenerated(int curve) const = 0;
  virtual Vec3 eval_curve(int curve, double t) const = 0;
  virtual Vec3 curve_tangent(int curve, double t) const = 0;  // d xyz / dt
  virtual bool curve_curvature(int curve, double t, double& k) const = 0;
  virtual double curve_length(int curve) const = 0;
  // End points (point ids) at t0 and t1.
  virtual int curve_start_point(int curve) const = 0;
  virtual int curve_end_point(int curve) const = 0;
  // uv of the curve at t on a face it bounds (side 1 is a seam's second pcurve).
  virtual Vec2 eval_pcurve(int curve, int face, int side, double t) const = 0;

  // --- points ---
  virtual Vec3 point_xyz(int point) const = 0;
};

// uv shifted by whole periods of face f to lie nearest `near`.
inline Vec2 unwrap_uv(const Geometry& g, int f, Vec2 uv, const Vec2& near) {
  for (int axis = 0; axis < 2; ++axis) {
    const double period = axis == 0 ? g.face_wrap_u(f) : g.face_wrap_v(f);
    if (period > 0) uv[axis] += period * std::round((near[axis] - uv[axis]) / period);
  }
  return uv;
}

}  // namespace sizemesh
