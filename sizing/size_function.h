// What the mesher asks of a size map: the wanted element size at a point.
#pragma once

#include "geometry/types.h"

namespace sizemesh {

class SizeFunction {
 public:
  virtual ~SizeFunction() = default;
  // Size at uv on a face (1-based id). `hint` is the caller's search start:
  // pass -1 when there is none; it is updated for the next nearby query.
  // Safe to call from several threads, each with its own hint.
  virtual double at(int face, const Vec2& uv, int& hint) const = 0;
  // Size at a point in space, for callers with no face or uv.
  virtual double at_xyz(const Vec3& xyz) const = 0;
};

// A uniform size everywhere (tests, and a fallback for debugging).
class UniformSize final : public SizeFunction {
 public:
  explicit UniformSize(double h) : h_(h) {}
  double at(int, const Vec2&, int&) const override { return h_; }
  double at_xyz(const Vec3&) const override { return h_; }

 private:
  double h_;
};

}  // namespace sizemesh
