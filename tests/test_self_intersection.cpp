// The self-intersection check (mesher/self_intersection.h) against hand-made
// configurations with known answers and against CGAL's exact count.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/predicates.h"
#include "mesher/self_intersection.h"
#include "tests/exact_intersections.h"

using namespace sizemesh;

namespace {

SurfaceMesh make(const std::vector<Vec3>& xyz, const std::vector<std::array<int, 3>>& tris) {
  SurfaceMesh m;
  m.xyz = xyz;
  m.tris = tris;
  m.tri_face.assign(tris.size(), 1);
  return m;
}

long long exact(const SurfaceMesh& m) {
  std::vector<std::array<double, 3>> p;
  for (const Vec3& x : m.xyz) p.push_back({x.x(), x.y(), x.z()});
  return test::exact_self_intersections(p, m.tris);
}

long long count(const SurfaceMesh& m) { return find_self_intersections(m, 100).pairs; }

}  // namespace

TEST_CASE("hand-made pairs: crossing, poking through a shared node, folded over a shared edge, duplicated") {
  // Two triangles crossing like a plus sign, no shared node.
  const SurfaceMesh cross = make({{0, 0, 0}, {2, 0, 0}, {1, 2, 0}, {1, 1, -1}, {1, 1, 1}, {1, -1, 0.5}},
                                 {{0, 1, 2}, {3, 4, 5}});
  CHECK(count(cross) == 1);
  // Apart by a hair above the plane: no intersection.
  const SurfaceMesh apart = make({{0, 0, 0}, {2, 0, 0}, {1, 2, 0}, {0, 0, 1e-300}, {2, 0, 1e-300}, {1, 2, 1e-300}},
                                 {{0, 1, 2}, {3, 4, 5}});
  CHECK(count(apart) == 0);
  // A fan of coplanar triangles around node 0 (a flat face): no intersection.
  const SurfaceMesh fan = make({{0, 0, 0}, {1, 0, 0}, {0.3, 0.9, 0}, {-0.8, 0.5, 0}, {-0.6, -0.7, 0}, {0.5, -0.8, 0}},
                               {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1}});
  CHECK(count(fan) == 0);
  // One shared node; the second triangle pokes through the first.
  const SurfaceMesh poke = make({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 0.5, -1}, {0.5, 1, 1}}, {{0, 1, 2}, {0, 3, 4}});
  CHECK(count(poke) == 1);
  // A shared edge folded flat onto the same side (a front that crossed itself).
  const SurfaceMesh fold = make({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.4, 0.6, 0}}, {{0, 1, 2}, {1, 0, 3}});
  CHECK(count(fold) == 1);
  // The same edge with the apexes on opposite sides: a valid pair.
  const SurfaceMesh flat = make({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.4, -0.6, 0}}, {{0, 1, 2}, {1, 0, 3}});
  CHECK(count(flat) == 0);
  // A duplicated triangle.
  const SurfaceMesh dup = make({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 1}});
  CHECK(count(dup) == 1);
  for (const SurfaceMesh* m : {&cross, &apart, &fan, &poke, &fold, &flat, &dup}) CHECK(count(*m) == exact(*m));
}

TEST_CASE("near-degenerate orientations are decided exactly") {
  // Points on a plane with coordinates that do not round to it exactly.
  const Vec3 a(0.1, 0.2, 0.3), b(0.7, 0.11, 0.13), c(0.3, 0.9, 0.17);
  for (double t : {0.25, 1.0 / 3.0, 0.6}) {
    const Vec3 d = a + t * (b - a) + (1 - t) * 0.5 * (c - a);  // on the plane up to rounding
    const int s = orient3d_sign(a, b, c, d);
    // The exact sign is antisymmetric under swapping two points.
    CHECK(orient3d_sign(b, a, c, d) == -s);
    CHECK(orient3d_sign(a, c, b, d) == -s);
  }
  CHECK(orient3d_sign(a, b, c, a) == 0);
  CHECK(orient3d_sign({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, 0}) == 0);
  CHECK(orient3d_sign({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, -1e-300}) == 1);
  CHECK(orient2d_sign({0.1, 0.1}, {0.3, 0.3}, {0.7, 0.7}) == 0);  // collinear, not representable slopes
  CHECK(orient2d_sign({1e-200, 0}, {1e200, 0}, {0, 1e-300}) == 1);  // a span too wide for fixed integers
}

TEST_CASE("random triangle soups: the count equals CGAL's exact count") {
  // Small random soups in a unit box with some shared nodes, so every rule is exercised.
  uint64_t state = 12345;
  auto next = [&]() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(state >> 11) / double(1ULL << 53);
  };
  for (int round = 0; round < 20; ++round) {
    std::vector<Vec3> xyz;
    for (int i = 0; i < 40; ++i) xyz.emplace_back(next(), next(), round % 2 ? 0.0 : next() * 0.1);
    std::vector<std::array<int, 3>> tris;
    for (int i = 0; i < 30; ++i) {
      const int a = int(next() * 40), b = int(next() * 40), c = int(next() * 40);
      if (a != b && b != c && a != c) tris.push_back({a, b, c});
    }
    const SurfaceMesh m = make(xyz, tris);
    INFO("round " << round);
    CHECK(count(m) == exact(m));
  }
}

TEST_CASE("the pairs kept are the smallest ones, whichever thread finds them") {
  // Two strips of 4,000 triangles each, crossing at right angles: every
  // triangle of one meets a few of the other, in blocks the threads take in
  // any order. The 50 pairs kept are the 50 smallest of all, on every run.
  std::vector<Vec3> xyz;
  std::vector<std::array<int, 3>> tris;
  const int n = 2000;
  for (int strip = 0; strip < 2; ++strip) {
    const int base = static_cast<int>(xyz.size());
    for (int i = 0; i <= n; ++i) {
      const double s = -1.0 + 2.0 * i / n;
      xyz.push_back(strip == 0 ? Vec3(s, -1, 0) : Vec3(0.3 * s, 0.3 * s, -1));
      xyz.push_back(strip == 0 ? Vec3(s, 1, 0) : Vec3(0.3 * s, 0.3 * s, 1));
    }
    for (int i = 0; i < n; ++i) {
      const int a = base + 2 * i;
      tris.push_back({a, a + 2, a + 1});
      tris.push_back({a + 1, a + 2, a + 3});
    }
  }
  const SurfaceMesh m = make(xyz, tris);
  const SelfIntersections all = find_self_intersections(m, static_cast<size_t>(-1));
  REQUIRE(all.pairs > 1000);
  REQUIRE(all.kept.size() == static_cast<size_t>(all.pairs));
  const std::vector<std::array<int, 3>>::size_type keep = 50;
  const std::vector<std::array<int, 2>> smallest(all.kept.begin(), all.kept.begin() + keep);
  for (int run = 0; run < 5; ++run) {
    const SelfIntersections some = find_self_intersections(m, keep);
    CHECK(some.pairs == all.pairs);
    CHECK(some.kept == smallest);
  }
}
