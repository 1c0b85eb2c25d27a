// A face's uv as the face mesher sees it: the surface's own parameters,
// stretched one direction at a time towards arc length where the surface's
// speed varies strongly across the face.
//
// Why: the front places points with the metric at an edge's midpoint, which
// holds only while the metric varies little across an element. A surface whose
// speed |dS/du| falls to zero at a boundary (a trailing edge or tip closed by
// coincident control points) or changes many times over (blended pods) breaks
// that: uv-straight edges bend in space and points land beside the boundary.
// Mapped so that the mean speed along each direction is about constant, the
// metric is nearly uniform again.
//
// Per direction (u, then v): the mean speed over lines across the face's uv
// box, taken in the middle of each interval between the map's knots (even
// steps and the surface's own knots, where a B-spline's speed may jump:
// exporters write rounded corners as spans each several times shorter than
// the last), integrated to a monotone piecewise-linear map w(u) over the same
// range (linear beyond it). Identity in a periodic direction and where the
// mean speed varies by less than kRatio; both maps identity for most faces.
#pragma once

#include <vector>

#include "core/geometry.h"

namespace sizemesh {

class UvStretch {
 public:
  static constexpr double kRatio = 20.0;  // max/min mean speed that turns a direction's map on

  UvStretch() = default;
  UvStretch(const Geometry& g, int face);

  Vec2 to_surface(const Vec2& w) const { return {axis_[0].forward(w.x()), axis_[1].forward(w.y())}; }
  Vec2 to_mesher(const Vec2& u) const { return {axis_[0].backward(u.x()), axis_[1].backward(u.y())}; }
  // d(surface uv)/d(mesher uv) per direction at w.
  Vec2 slope(const Vec2& w) const { return {axis_[0].slope(w.x()), axis_[1].slope(w.y())}; }
  bool stretched(int direction) const { return !axis_[direction].w.empty(); }

 private:
  // Monotone piecewise-linear map between surface parameter u and mesher
  // parameter w on matching knots; empty: identity.
  struct Axis {
    std::vector<double> u, w;
    double forward(double x) const { return w.empty() ? x : interpolate(w, u, x); }
    double backward(double x) const { return w.empty() ? x : interpolate(u, w, x); }
    double slope(double x) const;
    static double interpolate(const std::vector<double>& from, const std::vector<double>& to, double x);
  };
  Axis axis_[2];
};

}  // namespace sizemesh
