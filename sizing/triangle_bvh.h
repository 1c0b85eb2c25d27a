// Bounding-volume hierarchy over 3D triangles: ray casting with a filter.
//
// Inputs:  xyz #V points, tris #T triangles (vertex ids)
// Queries: closest hit of a ray within [0, t_max] among triangles the filter accepts;
//          the triangles nearest to a point.
#pragma once

#include <array>
#include <functional>
#include <utility>
#include <vector>

#include "geometry/types.h"

namespace sizemesh {

class TriangleBVH {
 public:
  TriangleBVH(const std::vector<Vec3>& xyz, const std::vector<std::array<int, 3>>& tris);

  struct Hit {
    int tri = -1;
    double t = 0;  // distance along the (unit) direction
  };
  // dir must be a unit vector. `accept(tri)` filters candidate triangles.
  Hit ray(const Vec3& origin, const Vec3& dir, double t_max, const std::function<bool(int)>& accept) const;
  // Triangles whose distance to p is at most the smallest such distance plus
  // `slack`, with their distances (branch and bound on box distances).
  std::vector<std::pair<int, double>> nearest(const Vec3& p, double slack) const;
  // Closest point of triangle abc to p, as barycentric weights of a, b, c.
  static Vec3 closest_barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int left = -1, right = -1;  // children; -1 for a leaf
    int begin = 0, end = 0;     // leaf range in order_
  };
  int build(int begin, int end);

  const std::vector<Vec3>& xyz_;
  const std::vector<std::array<int, 3>>& tris_;
  std::vector<int> order_;
  std::vector<Vec3> centroid_;
  std::vector<Node> nodes_;
};

}  // namespace sizemesh
