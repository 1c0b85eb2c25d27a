// Accuracy rules of a size field (core/size_field.h).
#include "core/size_field.h"

#include <cmath>

#include "core/geometry.h"

namespace sizemesh {

double deviation_size(double k, double delta) {
  if (!(k > 0) || !std::isfinite(k) || !(delta > 0)) return std::numeric_limits<double>::infinity();
  const double r = 1.0 / k;
  return delta >= r ? 2 * r : 2 * std::sqrt(2 * r * delta - delta * delta);  // chord of height delta
}

double face_deviation_size(const Geometry& g, int face, const Vec2& uv, double delta) {
  double k = 0;
  try {
    if (!g.max_curvature(face, uv, k)) return std::numeric_limits<double>::quiet_NaN();
  } catch (const Error&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return deviation_size(k, delta);
}

double SizeField::deviation_chord(const Geometry& g, int face, const Vec2& uv) const {
  const double cap = face_deviation_size(g, face, uv, accuracy_.deviation);
  return std::isnan(cap) ? std::numeric_limits<double>::infinity() : cap;
}

}  // namespace sizemesh
