// Gap sizes (paper 3.3): a thin slab by its solid side only, a flow domain's walls, none where bodies touch, slots.
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>

#include <catch2/catch.hpp>
#include <cmath>
#include <utility>

#include "cad/occt_model.h"
#include "sizing/proximity_size.h"
#include "sizing/refine_background.h"
#include "tests/sizing_checks.h"
#include "tests/test_models.h"

using namespace sizemesh;
using test::Sized;
using test::size_shape;

TEST_CASE("a thin closed slab is not refined across its thickness by default, fully with the solid side") {
  // 100 mm wide, 1 mm thick: the rays into the solid see the thickness, the
  // rays out of it see nothing.
  const double t = 1.0;
  Model m = model_from_shape(BRepPrimAPI_MakeBox(100.0, 100.0, t).Shape());
  REQUIRE(m.closed());
  BackgroundMesh bg = build_background_mesh(m);
  SizingParams p;
  const GapSizes by_default = gap_sizes(m, bg, p, 1000.0, 1e-6);
  p.gap_side = GapSide::Solid;
  const GapSizes solid = gap_sizes(m, bg, p, 1000.0, 1e-6);
  p.gap_side = GapSide::Both;
  const GapSizes both = gap_sizes(m, bg, p, 1000.0, 1e-6);
  REQUIRE(bg.num_vertices() >= 8);
  for (int v = 0; v < bg.num_vertices(); ++v) {
    CHECK(by_default.fluid[v] == kNoLimit);
    CHECK(by_default.solid[v] == kNoLimit);
    CHECK(solid.fluid[v] == kNoLimit);
    CHECK(solid.solid[v] == Approx(t / 2).epsilon(1e-9));  // BRepMesh puts every node on the rim
    CHECK(both.solid[v] == solid.solid[v]);
  }
  // With the background refined as in the pipeline, the big faces get inner
  // vertices: by default none is sized by the thickness, with the solid side all are.
  SizingParams q;
  q.h_max = 10;
  auto refined = [&](GapSide side) {
    q.gap_side = side;
    BackgroundMesh b = build_background_mesh(m);
    SizeMap map = refine_background(m, b, q, m.info().diagonal());
    return std::make_pair(std::move(b), std::move(map));
  };
  const auto [bd, d] = refined(GapSide::Auto);
  const auto [bs, s] = refined(GapSide::Solid);
  // Inner vertices of the two big faces (z = 0 and z = t).
  auto big = [&](const BackgroundMesh& b, int v) {
    return b.dim[v] == 2 && (std::abs(b.xyz[v].z()) < 1e-9 || std::abs(b.xyz[v].z() - t) < 1e-9);
  };
  int inner_default = 0, inner_solid = 0;
  for (int v = 0; v < bd.num_vertices(); ++v) {
    CHECK(d.limit[v] != Limit::Thickness);
    if (big(bd, v)) {
      ++inner_default;
      CHECK(d.h_initial[v] > 4 * t);
    }
  }
  for (int v = 0; v < bs.num_vertices(); ++v) {
    if (big(bs, v)) {
      CHECK(s.h_initial[v] <= t / 2 + 1e-12);
      ++inner_solid;
      CHECK(s.limit[v] == Limit::Thickness);
    }
  }
  CHECK(inner_default > 0);
  CHECK(inner_solid > 0);
}

TEST_CASE("in a flow domain (a solid with a cavity) the fluid is inside: gaps to the walls count, the body's thickness not") {
  // Domain: a 10 mm box. Body: a slab 1 mm thick, 0.3 mm above the floor.
  const TopoDS_Shape domain = BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(10.0, 10.0, 10.0).Shape(),
                                              BRepPrimAPI_MakeBox(gp_Pnt(2, 2, 0.3), 6.0, 6.0, 1.0).Shape())
                                  .Shape();
  Model m = model_from_shape(domain);
  REQUIRE(m.closed());
  CHECK(m.fluid_side() == -1);
  CHECK(model_from_shape(BRepPrimAPI_MakeBox(1.0, 1.0, 1.0).Shape()).fluid_side() == 1);
  BackgroundMesh bg = build_background_mesh(m);
  SizingParams p;
  const GapSizes by_default = gap_sizes(m, bg, p, 5.0, 1e-6);
  p.gap_side = GapSide::Solid;
  const GapSizes solid = gap_sizes(m, bg, p, 5.0, 1e-6);
  int under = 0, over = 0;
  for (int v = 0; v < bg.num_vertices(); ++v) {
    const Vec3& x = bg.xyz[v];
    const bool on_slab = x.x() > 2 - 1e-9 && x.x() < 8 + 1e-9 && x.y() > 2 - 1e-9 && x.y() < 8 + 1e-9;
    if (!on_slab) continue;
    if (std::abs(x.z() - 0.3) < 1e-9) {  // the slab's underside faces the floor across 0.3 of fluid
      ++under;
      CHECK(by_default.fluid[v] == Approx(0.15).epsilon(1e-9));
    }
    if (std::abs(x.z() - 1.3) < 1e-9) {  // its top rim (BRepMesh's only nodes) sees the side walls 2 away
      ++over;
      CHECK(by_default.fluid[v] == Approx(1.0).epsilon(1e-9));
    }
    CHECK(by_default.solid[v] == kNoLimit);
    if (std::abs(x.z() - 0.3) < 1e-9 || std::abs(x.z() - 1.3) < 1e-9) CHECK(solid.solid[v] == Approx(0.5).epsilon(1e-9));
  }
  CHECK(under >= 4);
  CHECK(over >= 4);
}

TEST_CASE("two boxes that touch make no gap, united or not") {
  // 1e-7 apart: far below the model tolerance (1e-5 of the diagonal), so
  // they touch; a gap size there would be 5e-8.
  const double apart = 1e-7;
  TopoDS_Compound pair;
  BRep_Builder b;
  b.MakeCompound(pair);
  b.Add(pair, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 10.0, 10.0, 1.0).Shape());
  b.Add(pair, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 1.0 + apart), 10.0, 10.0, 1.0).Shape());
  for (bool unite : {true, false}) {
    Model m = model_from_shape(pair, test::load_options(true, unite));
    REQUIRE(m.closed());
    BackgroundMesh bg = build_background_mesh(m);
    for (GapSide side : {GapSide::Auto, GapSide::Both}) {
      SizingParams p;
      p.gap_side = side;
      const GapSizes g = gap_sizes(m, bg, p, 100.0, 1e-5 * m.info().diagonal());
      int contact = 0;
      for (int v = 0; v < bg.num_vertices(); ++v) {
        if (std::abs(bg.xyz[v].z() - 1.0) > 2 * apart) continue;
        ++contact;
        CHECK(g.fluid[v] == kNoLimit);  // the other box's face: touching, no gap
      }
      CHECK(contact >= 4);
    }
  }
}

TEST_CASE("two parallel slabs close together get gap / mu_d in the slot by default, and only with gaps on") {
  const double gap = 0.1;  // through the fluid; each slab is ten times thicker
  TopoDS_Compound pair;
  BRep_Builder b;
  b.MakeCompound(pair);
  b.Add(pair, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 10.0, 10.0, 1.0).Shape());
  b.Add(pair, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 1.0 + gap), 10.0, 10.0, 1.0).Shape());
  SizingParams p;
  p.h_max = 5;
  Sized on = size_shape(pair, p);
  p.local_proximity = false;
  Sized off = size_shape(pair, p);
  REQUIRE(on.model.info().solids == 2);
  int facing = 0;
  for (int v = 0; v < on.bg.num_vertices(); ++v) {
    const Vec3& x = on.bg.xyz[v];
    const bool between = std::abs(x.z() - 1.0) < 1e-12 || std::abs(x.z() - 1.0 - gap) < 1e-12;
    if (!between) continue;
    ++facing;
    CHECK(on.m.h_proximity[v] == Approx(gap / 2).epsilon(1e-9));
    CHECK(on.m.limit[v] == Limit::Gap);
    CHECK(off.m.h_proximity[v] > 0.4);
  }
  CHECK(facing >= 8);
}
