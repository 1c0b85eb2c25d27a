// Bounding-volume hierarchy over 3D triangles: the one spatial index of the
// project, used by the proximity sizes (rays), the size query in xyz (closest
// triangle) and the mesh's self-intersection check (box overlaps).
//
// Inputs:  xyz #V points, tris #T triangles (vertex ids); the corners are
//          copied, so the hierarchy outlives the arrays it was built from.
// Queries: closest hit of a ray within [0, t_max] among triangles a filter accepts;
//          the triangles nearest to a point (all within a slack of the nearest);
//          the single closest triangle with the barycentric weights of the closest point;
//          every triangle whose box overlaps a given box.
#pragma once

#include <array>
#include <functional>
#include <utility>
#include <vector>

#include "core/types.h"

namespace sizemesh {

class TriangleBVH {
 public:
  using Box = Eigen::AlignedBox3d;

  TriangleBVH(const std::vector<Vec3>& xyz, const std::vector<std::array<int, 3>>& tris);

  int size() const { return static_cast<int>(corners_.size()); }
  const std::array<Vec3, 3>& corners(int tri) const { return corners_[tri]; }
  const Box& box(int tri) const { return boxes_[tri]; }

  struct Hit {
    int tri = -1;
    double t = 0;  // distance along the (unit) direction
  };
  // dir must be a unit vector. `accept(tri)` filters candidate triangles.
  Hit ray(const Vec3& origin, const Vec3& dir, double t_max, const std::function<bool(int)>& accept) const;

  // Triangles whose distance to p is at most the smallest such distance plus
  // `slack`, with their distances (branch and bound on box distances).
  std::vector<std::pair<int, double>> nearest(const Vec3& p, double slack) const;

  struct Closest {
    int tri = -1;
    Vec3 weights{0, 0, 0};  // barycentric weights of the closest point on `tri`
    double distance2 = 0;
  };
  // The closest triangle to p (the first found among equals), nearer subtree first.
  Closest closest(const Vec3& p) const;

  // Calls visit(tri) for every triangle whose bounding box overlaps `query`.
  template <class Visit>
  void overlapping(const Box& query, Visit&& visit) const {
    if (nodes_.empty()) return;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (!n.box.intersects(query)) continue;
      if (n.left < 0) {
        for (int i = n.begin; i < n.end; ++i)
          if (boxes_[order_[i]].intersects(query)) visit(order_[i]);
      } else if (top + 2 <= 128) {
        stack[top++] = n.left;
        stack[top++] = n.right;
      }
    }
  }

  // Closest point of triangle abc to p, as barycentric weights of a, b, c.
  static Vec3 closest_barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

 private:
  struct Node {
    Box box;
    int left = -1, right = -1;  // children; -1 for a leaf
    int begin = 0, end = 0;     // leaf range in order_
  };
  // The subtree over order_[begin, end) into nodes_[id ...] (pre-order:
  // its left child at id + 1, its right child after the left subtree's
  // nodes), large subtrees on two tasks: the same tree for any thread count.
  void build(int id, int begin, int end);
  // Nodes of the subtree over m triangles: 1 for m <= 4, else 1 + f(m / 2) + f(m - m / 2).
  static int subtree_nodes(int m);
  static constexpr int kParallelBuild = 20000;  // triangles under a node whose halves are built as two tasks

  std::vector<std::array<Vec3, 3>> corners_;
  std::vector<int> order_;
  std::vector<Vec3> centroid_;  // during the build only
  std::vector<Box> boxes_;      // #T
  std::vector<Node> nodes_;
};

}  // namespace sizemesh
