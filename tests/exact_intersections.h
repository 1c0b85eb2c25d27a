// An independent, exact self-intersection count for the tests: CGAL's box
// intersection for candidates and its exact predicates for every pair, with
// the same rules by shared nodes as the product's check (mesher/self_intersection.h).
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <array>
#include <vector>

namespace sizemesh::test {

// Pairs of triangles (node ids into xyz) that meet beyond their shared nodes;
// zero-area triangles are left out, as in the product.
inline long long exact_self_intersections(const std::vector<std::array<double, 3>>& xyz,
                                          const std::vector<std::array<int, 3>>& tris) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using P = K::Point_3;
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;
  std::vector<P> p;
  p.reserve(xyz.size());
  for (const auto& x : xyz) p.emplace_back(x[0], x[1], x[2]);
  std::vector<Box> boxes;
  for (size_t i = 0; i < tris.size(); ++i) {
    const auto& t = tris[i];
    if (CGAL::collinear(p[t[0]], p[t[1]], p[t[2]])) continue;
    boxes.emplace_back(p[t[0]].bbox() + p[t[1]].bbox() + p[t[2]].bbox(), static_cast<int>(i));
  }
  long long count = 0;
  auto check = [&](const Box& x, const Box& y) {
    const auto &A = tris[x.info()], &C = tris[y.info()];
    const K::Triangle_3 ta(p[A[0]], p[A[1]], p[A[2]]), tc(p[C[0]], p[C[1]], p[C[2]]);
    int shared = 0, ia = -1, ic = -1;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (A[i] == C[j]) {
          ++shared;
          ia = i;
          ic = j;
        }
    bool hit = false;
    if (shared == 0) {
      hit = CGAL::do_intersect(ta, tc);
    } else if (shared == 3) {
      hit = true;
    } else if (shared == 1) {
      hit = CGAL::do_intersect(K::Segment_3(p[A[(ia + 1) % 3]], p[A[(ia + 2) % 3]]), tc) ||
            CGAL::do_intersect(K::Segment_3(p[C[(ic + 1) % 3]], p[C[(ic + 2) % 3]]), ta);
    } else {
      int aa = 0, ac = 0;
      for (int i = 0; i < 3; ++i) {
        if (A[i] != C[0] && A[i] != C[1] && A[i] != C[2]) aa = i;
        if (C[i] != A[0] && C[i] != A[1] && C[i] != A[2]) ac = i;
      }
      const P &u = p[A[(aa + 1) % 3]], &w = p[A[(aa + 2) % 3]];
      hit = CGAL::coplanar(u, w, p[A[aa]], p[C[ac]]) &&
            CGAL::coplanar_orientation(u, w, p[A[aa]], p[C[ac]]) == CGAL::POSITIVE;
    }
    count += hit;
  };
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), check);
  return count;
}

}  // namespace sizemesh::test
