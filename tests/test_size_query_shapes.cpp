// The size query on OCCT primitives: one size across periodic seams, at_xyz near vertices, safe from several threads.
#include <catch2/catch.hpp>

#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>

#include <algorithm>
#include <cmath>
#include <random>
#include <thread>

#include "background/background_mesh.h"
#include "cad/occt_model.h"
#include "sizing/size_query.h"
#include "tests/size_query_checks.h"

using namespace sizemesh;
using test::Case;
using test::make_case;
using test::proper;
using test::same;
using test::sample;

TEST_CASE("a sphere, a cylinder and a torus answer the same at u and u + period, across the seam", "[size_query]") {
  for (int shape = 0; shape < 3; ++shape) {
    const Model model = shape == 0   ? model_from_shape(BRepPrimAPI_MakeSphere(2.0).Shape())
                        : shape == 1 ? model_from_shape(BRepPrimAPI_MakeCylinder(1.0, 3.0).Shape())
                                     : model_from_shape(BRepPrimAPI_MakeTorus(3.0, 1.0).Shape());
    const Case c = make_case(shape == 0 ? "sphere" : shape == 1 ? "cylinder" : "torus", model);
    INFO(c.name);
    const SizeQuery query(c.bg, c.h, c.period_u, c.period_v);
    std::mt19937 rng(99);
    int periodic_faces = 0, v_periodic_faces = 0, checks = 0;
    for (const FacePatch& patch : c.bg.patches) {
      const double P = c.period_u[patch.face - 1], Pv = c.period_v[patch.face - 1];
      if (patch.tris.empty() || !(P > 0)) continue;
      ++periodic_faces;
      v_periodic_faces += Pv > 0;
      std::uniform_int_distribution<int> pick(0, static_cast<int>(patch.tris.size()) - 1);
      for (int i = 0; i < 300; ++i) {
        const int t = pick(rng);
        if (!proper(patch, t)) continue;
        const Vec2 p = sample(patch, t, rng);
        const SizeQuery::Hit base = query.locate(patch.face, p, -1);
        const SizeQuery::Hit ref = query.locate_brute_force(patch.face, p);
        CHECK(same(base, ref));
        for (double shift : {P, -P, 2 * P}) {
          int hint = i % 2 ? base.tri : -1;
          const double h = query.at(patch.face, Vec2(p.x() + shift, p.y()), hint);
          CHECK(std::abs(h - base.h) <= 1e-12 * base.h);
          ++checks;
        }
        if (Pv > 0)
          for (const Vec2& shift : {Vec2(0, Pv), Vec2(P, -Pv), Vec2(-3 * P, 2 * Pv)}) {
            int hint = i % 2 ? base.tri : -1;
            const double h = query.at(patch.face, p + shift, hint);
            CHECK(std::abs(h - base.h) <= 1e-12 * base.h);
            ++checks;
          }
      }
      // Points on and just across the seam, walking from a hint on the other side.
      double umin = patch.uv[0].x(), umax = umin, vmin = patch.uv[0].y(), vmax = vmin;
      for (const Vec2& uv : patch.uv) {
        umin = std::min(umin, uv.x());
        umax = std::max(umax, uv.x());
        vmin = std::min(vmin, uv.y());
        vmax = std::max(vmax, uv.y());
      }
      CHECK(umax - umin == Approx(P));
      for (int i = 1; i < 20; ++i) {
        const double v = vmin + (vmax - vmin) * i / 20.0;
        int hint = -1;
        const double h0 = query.at(patch.face, Vec2(umin, v), hint);
        const double h1 = query.at(patch.face, Vec2(umax, v), hint);
        CHECK(std::abs(h1 - h0) <= 1e-9 * h0);
        const double eps = 1e-9 * P;
        const double ha = query.at(patch.face, Vec2(umin - eps, v), hint);
        const double hb = query.at(patch.face, Vec2(umax + eps, v), hint);
        CHECK(std::abs(ha - h0) <= 1e-6 * h0);
        CHECK(std::abs(hb - h0) <= 1e-6 * h0);
        checks += 3;
      }
    }
    CHECK(periodic_faces >= 1);
    CHECK((shape != 2 || v_periodic_faces >= 1));
    CHECK(checks > 100);
    CHECK(query.stats().outside == 0);
  }
}

TEST_CASE("at_xyz returns the vertex size at background vertices and stays within the sizes nearby",
          "[size_query]") {
  const Model model = model_from_shape(BRepPrimAPI_MakeCylinder(1.0, 3.0).Shape());
  const Case c = make_case("cylinder", model);
  const SizeQuery query(c.bg, c.h, c.period_u, c.period_v);
  const double hmin = *std::min_element(c.h.begin(), c.h.end()), hmax = *std::max_element(c.h.begin(), c.h.end());
  for (size_t v = 0; v < c.bg.xyz.size(); ++v) {
    CHECK(query.at_xyz(c.bg.xyz[v]) == Approx(c.h[v]).epsilon(1e-12));
    const double off = query.at_xyz(c.bg.xyz[v] * 1.01 + Vec3(0, 0, 0.001));
    CHECK(off >= hmin);
    CHECK(off <= hmax);
  }
}

TEST_CASE("at() is safe from several threads and its counters add up", "[size_query]") {
  const Model model = model_from_shape(BRepPrimAPI_MakeSphere(1.0).Shape());
  const Case c = make_case("sphere", model);
  SizeQuery query(c.bg, c.h, c.period_u, c.period_v);
  const FacePatch& patch = c.bg.patches[0];
  REQUIRE(!patch.tris.empty());
  auto work = [&](int seed, double* sum) {
    std::mt19937 rng(seed);
    int hint = -1;
    for (int i = 0; i < 20000; ++i) {
      const int t = static_cast<int>(rng() % patch.tris.size());
      if (!proper(patch, t)) continue;
      const Vec2 p = sample(patch, t, rng);
      const double h = query.at(patch.face, p, hint);
      const double ref = query.locate_brute_force(patch.face, p).h;
      if (std::abs(h - ref) > 1e-12 * ref) *sum += 1;
    }
  };
  double bad1 = 0, bad2 = 0, bad0 = 0;
  std::thread a(work, 1, &bad1), b(work, 2, &bad2);
  work(3, &bad0);
  a.join();
  b.join();
  CHECK(bad0 + bad1 + bad2 == 0);
  const QueryStats st = query.stats();
  CHECK(st.queries > 30000);
  CHECK(st.queries <= 60000);
  CHECK(st.mean_visited() >= 1);
  query.reset_stats();
  CHECK(query.stats().queries == 0);
}
