// Basic value types shared by every part of sizemesh.
#pragma once

#include <Eigen/Dense>
#include <stdexcept>
#include <string>

namespace sizemesh {

using Vec2 = Eigen::Vector2d;  // a point in a face's parameter (uv) space
using Vec3 = Eigen::Vector3d;  // a point in model space (xyz, file units)

// The one exception type: its message is a sentence for the user.
struct Error : std::runtime_error {
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace sizemesh
