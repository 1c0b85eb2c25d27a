// One face's surface and size as the face mesher sees them: position, first
// derivatives, unit natural normal and the wanted size h at a uv, with the
// metric M = J^T J / h^2 (J = [du dv]) in which a unit edge has the wanted length.
//
// The uv here is the mesher's (mesher/uv_stretch.h): the surface's own
// parameters, stretched where its speed varies strongly; to_surface() and
// to_mesher() convert, and the samples' derivatives are taken in the mesher's uv.
//
// Inputs: the B-rep, the size function and a face id.
// Outputs: samples at uv; projections of points in space onto the face (uv).
// Not thread-safe (keeps the size query hint); one per face and thread.
#pragma once

#include <Eigen/Dense>

#include "core/geometry.h"
#include "mesher/uv_stretch.h"
#include "core/size_field.h"

namespace sizemesh {

struct SurfaceSample {
  Vec3 p, du, dv;
  Vec3 n;        // unit (du x dv), zero where the surface is singular (poles)
  double h = 0;  // wanted edge length (model units)

  // Metric M = J^T J / h^2, regularised where J is singular.
  Eigen::Matrix2d metric() const {
    Eigen::Matrix2d m;
    m << du.dot(du), du.dot(dv), du.dot(dv), dv.dot(dv);
    m /= h * h;
    m += 1e-10 * m.trace() * Eigen::Matrix2d::Identity();
    return m;
  }
};

class FaceSurface {
 public:
  FaceSurface(const Geometry& g, const SizeField& h, int face);

  SurfaceSample eval(const Vec2& uv);
  // The same without the size (h left 0): for moves that do not need it.
  SurfaceSample eval_shape(const Vec2& uv) const;
  // A triangle with corners ua, ub, uc and normal nt in space turns against
  // the surface at its uv centroid (the quality report's inverted triangle),
  // or the surface cannot be evaluated there.
  bool turned_at_centroid(const Vec2& ua, const Vec2& ub, const Vec2& uc, const Vec3& nt) const;
  // Nearest point of the surface to xyz, from the start uv; the result is
  // shifted by whole periods to lie closest to the start. False if it fails.
  bool project(const Vec3& xyz, Vec2& uv) const;
  // uv shifted by whole periods to lie closest to `near`.
  Vec2 unwrap(Vec2 uv, const Vec2& near) const;
  // uv moved out of a band along a side of the uv box where the surface does
  // not move across it (a knot span whose control points coincide row by
  // row, as some exporters write at a trailing edge): to the band's inner
  // edge, the same point in space where the derivatives are defined again.
  // uv itself where the face has no such band.
  Vec2 off_band(const Vec2& uv) const;
  bool has_band() const { return banded_; }
  // Between the mesher's uv and the surface's own parameters.
  Vec2 to_surface(const Vec2& uv) const { return stretch_.to_surface(uv); }
  Vec2 to_mesher(const Vec2& uv) const { return stretch_.to_mesher(uv); }

  const Geometry& geometry() const { return g_; }
  const SizeField& size_field() const { return h_; }
  int face() const { return face_; }
  long long size_queries = 0;

 private:
  const Geometry& g_;
  const SizeField& h_;
  int face_;
  int hint_ = -1;
  double period_u_, period_v_;
  double fallback_h_;  // used where h is not a positive number
  UvStretch stretch_;
  UVBox box_;            // the face's uv box (surface uv)
  UVBox live_;           // the same without its bands
  bool banded_ = false;
};

}  // namespace sizemesh
