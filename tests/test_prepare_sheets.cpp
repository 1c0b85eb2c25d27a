// Preparing open sheets and shells: plates and a fin standing on a body are imprinted, an open box's flat mouth capped.
#include <catch2/catch.hpp>

#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <gp_Ax2.hxx>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "cad/occt_model.h"
#include "tests/prepare_checks.h"

using namespace sizemesh;
using test::compound;
using test::mesh_checked;
using test::quad;
using test::total_area;

namespace {

// Triangles using each mesh edge.
std::map<std::pair<int, int>, int> edge_uses(const SurfaceMesh& m) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : m.tris)
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
  return uses;
}

}  // namespace

TEST_CASE("a T of two plates is imprinted: the junction curve is shared by three faces, no triangle twice") {
  // Base plate z = 0 (x 0..2, y 0..1); stem plate x = 1 standing on it (z 0..1).
  const TopoDS_Shape base = quad({0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0});
  const TopoDS_Shape stem = quad({1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1});
  const Model model = model_from_shape(compound({base, stem}));
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 2);
  CHECK(p.sheets_imprinted == 2);
  CHECK(p.fallback.empty());
  REQUIRE(model.num_faces() == 3);  // the base cut in two along x = 1, the stem
  CHECK(total_area(model) == Approx(3.0).epsilon(1e-12));
  std::map<int, int> uses;
  for (int f = 1; f <= 3; ++f)
    for (const auto& loop : model.face_loops(f))
      for (const auto& use : loop) ++uses[use.curve];
  int junction = 0, on_line = 0;
  for (const auto& [c, n] : uses) {
    if (n != 3) continue;
    ++junction;
    double t0, t1;
    model.curve_range(c, t0, t1);
    for (double t : {t0, 0.5 * (t0 + t1), t1}) {
      const Vec3 x = model.eval_curve(c, t);
      on_line += std::abs(x.x() - 1) < 1e-9 && std::abs(x.z()) < 1e-9;
    }
  }
  CHECK(junction == 1);
  CHECK(on_line == 3);

  const auto [m, q] = mesh_checked(model, 0.1);
  std::set<std::array<int, 3>> seen;
  for (const auto& t : m.tris) {
    std::array<int, 3> key = t;
    std::sort(key.begin(), key.end());
    CHECK(seen.insert(key).second);  // no duplicate triangle
  }
  // Mesh edges on the junction are used by three triangles; no other edge is.
  int triple = 0;
  for (const auto& [e, n] : edge_uses(m)) {
    if (n < 3) continue;
    ++triple;
    CHECK(n == 3);
    for (int v : {e.first, e.second}) {
      CHECK(std::abs(m.xyz[v].x() - 1) < 1e-9);
      CHECK(std::abs(m.xyz[v].z()) < 1e-9);
    }
  }
  CHECK(triple >= 10);  // the 1-long junction at h = 0.1
  CHECK(q.nonmanifold_edges == triple);
}

TEST_CASE("a sheet fin standing on a cylinder fuselage is imprinted on it, its part inside dropped") {
  // Fin: the plane y = 0, x 4..6, z 0.5..2, so it enters the fuselage (radius 1).
  const TopoDS_Shape fuselage = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)), 1.0, 10.0).Shape();
  const TopoDS_Shape fin = quad({4, 0, 0.5}, {6, 0, 0.5}, {6, 0, 2}, {4, 0, 2});
  const Model model = model_from_shape(compound({fuselage, fin}));
  const Preparation& p = model.info().preparation;
  CHECK(p.sheets_imprinted == 1);
  CHECK(p.sheet_pieces_dropped == 1);
  CHECK(p.fallback.empty());
  // Fuselage area, plus the fin above z = 1 (2 x 1).
  CHECK(total_area(model) == Approx(2 * kPi * 10 + 2 * kPi + 2.0).epsilon(1e-9));
  const auto [m, q] = mesh_checked(model, 0.1);
  // Free edges only on the fin's three outer sides (x = 4, x = 6, z = 2).
  for (const auto& [e, n] : edge_uses(m)) {
    if (n != 1) continue;
    const Vec3 mid = 0.5 * (m.xyz[e.first] + m.xyz[e.second]);
    CHECK(std::abs(mid.y()) < 1e-9);
    CHECK(mid.z() > 1 - 1e-9);
  }
}

TEST_CASE("fuselage, wing through it and sheet fin on it: one surface, exact area, conforming junctions") {
  const TopoDS_Shape fuselage = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)), 1.0, 10.0).Shape();
  const TopoDS_Shape wing = BRepPrimAPI_MakeBox(gp_Pnt(3, -6, -0.2), 2.0, 12.0, 0.4).Shape();
  const TopoDS_Shape fin = quad({6, 0, 0.5}, {8, 0, 0.5}, {8, 0, 2.5}, {6, 0, 2.5});
  const Model model = model_from_shape(compound({fuselage, wing, fin}));
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 3);
  CHECK(p.fused);
  CHECK(p.sheets_imprinted == 1);
  CHECK(p.sheet_pieces_dropped == 1);
  CHECK(p.fallback.empty());
  CHECK(model.num_faces() == 14);  // the 13 of the wing-body union and the fin above z = 1
  const double s = 0.2, c = std::sqrt(1 - s * s);
  const double cylinder = 2 * kPi * 10 + 2 * kPi - 2 * 2 * (2 * std::asin(s));
  const double box = 2 * (2 * 12 + 2 * 0.4 + 12 * 0.4) - 2 * (2 * 2 * c) - 2 * 2 * (s * c + std::asin(s));
  CHECK(total_area(model) == Approx(cylinder + box + 2 * 1.5).epsilon(1e-3));
  const auto [m, q] = mesh_checked(model, 0.1);
  // Watertight but for the fin's three free sides (x = 6, x = 8, z = 2.5);
  // the fin's root on the fuselage is used by three triangles.
  int open = 0, root = 0;
  for (const auto& [e, n] : edge_uses(m)) {
    CHECK(n <= 3);
    if (n == 3) {
      ++root;
      for (int v : {e.first, e.second}) {
        CHECK(std::abs(m.xyz[v].y()) < 1e-9);
        CHECK(std::abs(m.xyz[v].z() - 1) < 1e-9);
      }
    }
    if (n != 1) continue;
    ++open;
    const Vec3 mid = 0.5 * (m.xyz[e.first] + m.xyz[e.second]);
    CHECK(std::abs(mid.y()) < 1e-9);
    CHECK(mid.z() > 1 - 1e-9);
  }
  CHECK(open >= 3 * 10);
  CHECK(root >= 10);
  CHECK(q.nonmanifold_edges == root);
}

TEST_CASE("an open box whose mouth lies flat is capped there and united with the box it reaches out of") {
  // A: the unit cube. B: a box x 0.5..1.5, y and z 0.25..0.75, without its
  // face at x = 1.5, so it reaches out of A through A's face x = 1. Its free
  // curves are one flat loop: a planar cap closes it (an OpenVSP tip or strut
  // root exported without its cap), and the union keeps what lies outside A.
  const TopoDS_Shape a = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 1.0, 1.0, 1.0).Shape();
  const double x0 = 0.5, x1 = 1.5, lo = 0.25, hi = 0.75;
  const TopoDS_Shape b = compound({quad({x0, lo, lo}, {x0, hi, lo}, {x0, hi, hi}, {x0, lo, hi}),
                                   quad({x0, lo, lo}, {x1, lo, lo}, {x1, hi, lo}, {x0, hi, lo}),
                                   quad({x0, lo, hi}, {x1, lo, hi}, {x1, hi, hi}, {x0, hi, hi}),
                                   quad({x0, lo, lo}, {x1, lo, lo}, {x1, lo, hi}, {x0, lo, hi}),
                                   quad({x0, hi, lo}, {x1, hi, lo}, {x1, hi, hi}, {x0, hi, hi})});
  const Model model = model_from_shape(compound({a, b}));
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 2);
  CHECK(p.components[0].role == "solid");
  CHECK(p.components[1].role == "solid");
  CHECK(p.components[1].free_curves == 4);
  CHECK(p.components[1].caps_added == 1);
  CHECK(p.caps_added == 1);
  CHECK(p.not_united.empty());
  CHECK(model.closed());
  // The cube less the square B covers on x = 1, plus B's four sides beyond
  // x = 1 (0.5 x 0.5 each) and its cap at x = 1.5.
  CHECK(total_area(model) == Approx(6.0 - 0.25 + 4 * 0.25 + 0.25).epsilon(1e-9));
  const auto [m, q] = mesh_checked(model, 0.05);
  for (const auto& [e, n] : edge_uses(m)) CHECK(n == 2);
}
