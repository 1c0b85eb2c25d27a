// Basic value types shared by every part of sizemesh.
#pragma once

#include <Eigen/Dense>
#include <stdexcept>
#include <string>

namespace sizemesh {

using Vec2 = Eigen::Vector2d;  // a point in a face's parameter (uv) space
using Vec3 = Eigen::Vector3d;  // a point in model space (xyz, file units)

constexpr double kPi = 3.14159265358979323846;

// The exception type: its message is a sentence for the user.
struct Error : std::runtime_error {
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// A surface or curve the kernel cannot evaluate at one parameter (outside its
// range, at a degenerate spot): the mesher catches it and tries elsewhere.
struct EvaluationError : Error {
  using Error::Error;
};

}  // namespace sizemesh
