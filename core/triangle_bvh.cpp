#include "core/triangle_bvh.h"

#include <oneapi/tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace sizemesh {

TriangleBVH::TriangleBVH(const std::vector<Vec3>& xyz, const std::vector<std::array<int, 3>>& tris) {
  const int n = static_cast<int>(tris.size());
  corners_.resize(n);
  order_.resize(n);
  centroid_.resize(n);
  for (int t = 0; t < n; ++t) {
    for (int k = 0; k < 3; ++k) corners_[t][k] = xyz[tris[t][k]];
    order_[t] = t;
    centroid_[t] = (xyz[tris[t][0]] + xyz[tris[t][1]] + xyz[tris[t][2]]) / 3.0;
  }
  if (n > 0) {
    nodes_.resize(subtree_nodes(n));
    build(0, 0, n);
  }
  std::vector<Vec3>().swap(centroid_);  // only the build needs them
  boxes_.resize(n);
  for (int t = 0; t < n; ++t)
    for (const Vec3& p : corners_[t]) boxes_[t].extend(p);
}

namespace {

// (f(m), f(m + 1)) for f = TriangleBVH::subtree_nodes, in O(log m): the
// halves of m and m + 1 are j and j + 1 for j = m / 2.
std::pair<int, int> subtree_pair(int m) {
  if (m <= 3) return {1, 1};
  if (m == 4) return {1, 3};
  const auto [fj, fj1] = subtree_pair(m / 2);
  return m % 2 == 0 ? std::make_pair(1 + 2 * fj, 1 + fj + fj1) : std::make_pair(1 + fj + fj1, 1 + 2 * fj1);
}

}  // namespace

int TriangleBVH::subtree_nodes(int m) { return subtree_pair(m).first; }

// Median split along the longest axis of the centroids' box.
void TriangleBVH::build(int id, int begin, int end) {
  Eigen::AlignedBox3d box, cbox;
  for (int i = begin; i < end; ++i) {
    for (const Vec3& p : corners_[order_[i]]) box.extend(p);
    cbox.extend(centroid_[order_[i]]);
  }
  nodes_[id].box = box;
  if (end - begin <= 4) {
    nodes_[id].begin = begin;
    nodes_[id].end = end;
    return;
  }
  int axis;
  cbox.sizes().maxCoeff(&axis);
  const int mid = (begin + end) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](int a, int b) { return centroid_[a][axis] < centroid_[b][axis]; });
  const int l = id + 1, r = id + 1 + subtree_nodes(mid - begin);
  nodes_[id].left = l;
  nodes_[id].right = r;
  if (end - begin >= kParallelBuild) {
    tbb::parallel_invoke([&] { build(l, begin, mid); }, [&] { build(r, mid, end); });
  } else {
    build(l, begin, mid);
    build(r, mid, end);
  }
}

namespace {
// Slab test: entry distance of the ray into the box, or +inf when missed.
// Axis-parallel directions are handled apart (0 * inf would give NaN).
double ray_box(const Eigen::AlignedBox3d& b, const Vec3& o, const Vec3& d, const Vec3& inv, double t_max) {
  double t0 = 0, t1 = t_max;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) {
      if (o[k] < b.min()[k] || o[k] > b.max()[k]) return INFINITY;
      continue;
    }
    double a = (b.min()[k] - o[k]) * inv[k], c = (b.max()[k] - o[k]) * inv[k];
    if (a > c) std::swap(a, c);
    t0 = std::max(t0, a);
    t1 = std::min(t1, c);
    if (t0 > t1) return INFINITY;
  }
  return t0;
}

// Moller-Trumbore; returns the distance or +inf. Hits on a triangle's edges
// and corners count (a ray along a face's rim lands exactly on them).
double ray_triangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a, p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-300) return INFINITY;
  const double inv = 1.0 / det;
  const Vec3 s = o - a;
  const double u = s.dot(p) * inv;
  constexpr double eps = 1e-9;
  if (u < -eps || u > 1 + eps) return INFINITY;
  const Vec3 q = s.cross(e1);
  const double v = d.dot(q) * inv;
  if (v < -eps || u + v > 1 + eps) return INFINITY;
  const double t = e2.dot(q) * inv;
  return t >= 0 ? t : INFINITY;
}
}  // namespace

TriangleBVH::Hit TriangleBVH::ray(const Vec3& origin, const Vec3& dir, double t_max,
                                  const std::function<bool(int)>& accept) const {
  Hit best;
  best.t = t_max;
  if (nodes_.empty()) return best;
  const Vec3 inv(1.0 / dir.x(), 1.0 / dir.y(), 1.0 / dir.z());
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top) {
    const Node& n = nodes_[stack[--top]];
    if (ray_box(n.box, origin, dir, inv, best.t) == INFINITY) continue;
    if (n.left < 0) {
      for (int i = n.begin; i < n.end; ++i) {
        const int t = order_[i];
        const auto& c = corners_[t];
        const double d = ray_triangle(origin, dir, c[0], c[1], c[2]);
        if (d < best.t && accept(t)) {
          best.t = d;
          best.tri = t;
        }
      }
    } else if (top + 2 <= 128) {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
  return best;
}

// Ericson's closest point on a triangle, by Voronoi regions.
Vec3 TriangleBVH::closest_barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = d1 / (d1 - d3);
    return {1 - t, t, 0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    return {1 - t, 0, t};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - t, t};
  }
  const double denom = va + vb + vc;
  if (!(denom > 0)) return {1, 0, 0};  // degenerate in xyz
  const double v = vb / denom, w = vc / denom;
  return {1 - v - w, v, w};
}

std::vector<std::pair<int, double>> TriangleBVH::nearest(const Vec3& p, double slack) const {
  std::vector<std::pair<int, double>> found;
  if (nodes_.empty()) return found;
  double best = INFINITY;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top) {
    const Node& n = nodes_[stack[--top]];
    if (n.box.exteriorDistance(p) > best + slack) continue;
    if (n.left < 0) {
      for (int i = n.begin; i < n.end; ++i) {
        const auto& c = corners_[order_[i]];
        const Vec3 w = closest_barycentric(p, c[0], c[1], c[2]);
        const double d = (w[0] * c[0] + w[1] * c[1] + w[2] * c[2] - p).norm();
        if (d <= best + slack) found.emplace_back(order_[i], d);
        best = std::min(best, d);
      }
    } else if (top + 2 <= 128) {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
  found.erase(std::remove_if(found.begin(), found.end(), [&](const auto& f) { return f.second > best + slack; }),
              found.end());
  return found;
}

namespace {
// Squared distance from p to an axis-aligned box (0 inside).
double box_distance2(const Vec3& p, const Eigen::AlignedBox3d& b) {
  return (p - p.cwiseMax(b.min()).cwiseMin(b.max())).squaredNorm();
}
}  // namespace

TriangleBVH::Closest TriangleBVH::closest(const Vec3& p) const {
  Closest best;
  best.distance2 = INFINITY;
  if (nodes_.empty()) return best;
  int stack[128];  // median splits: depth <= log2(#T) < 32
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (box_distance2(p, n.box) >= best.distance2) continue;
    if (n.left < 0) {
      for (int i = n.begin; i < n.end; ++i) {
        const auto& c = corners_[order_[i]];
        const Vec3 w = closest_barycentric(p, c[0], c[1], c[2]);
        const double d2 = (w[0] * c[0] + w[1] * c[1] + w[2] * c[2] - p).squaredNorm();
        if (d2 < best.distance2) best = {order_[i], w, d2};
      }
      continue;
    }
    if (top + 2 > 128) continue;
    // Nearer child last, so it is visited first.
    const double dl = box_distance2(p, nodes_[n.left].box), dr = box_distance2(p, nodes_[n.right].box);
    stack[top++] = dl < dr ? n.right : n.left;
    stack[top++] = dl < dr ? n.left : n.right;
  }
  return best;
}

}  // namespace sizemesh
