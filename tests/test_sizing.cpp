// Size map (paper 3.2-3.4): initial sizes on analytic shapes, exact gradation
// smoothing on every shared model, local controls where set and nowhere else.
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "cad/occt_model.h"
#include "sizing/initial_sizes.h"
#include "sizing/lp_smooth.h"
#include "sizing/proximity_size.h"
#include "sizing/refine_background.h"
#include "sizing/smooth.h"
#include "tests/cli_runner.h"
#include "tests/stage_runs.h"
#include "tests/test_models.h"

using namespace sizemesh;

namespace {

// Only curvature counts: no proximity, no gaps, bounds far away.
SizingParams curvature_only(double phi_deg) {
  SizingParams p;
  p.phi_c_deg = phi_deg;
  p.mu_d = 1e-9;  // huge proximity sizes
  p.local_proximity = false;
  p.h_min = 1e-9;
  p.h_max = 1e9;
  return p;
}

struct Sized {
  Model model;
  BackgroundMesh bg;
  SizeMap m;
};

Sized size_shape(const TopoDS_Shape& shape, const SizingParams& p) {
  Model model = model_from_shape(shape);
  BackgroundMesh bg = build_background_mesh(model);
  SizeMap m = initial_sizes(model, bg, p, model.info().diagonal());
  return {std::move(model), std::move(bg), std::move(m)};
}

}  // namespace

TEST_CASE("sphere of radius r gives h_c = 2 r sin(phi_c / 2) at every vertex, poles included") {
  const double r = 2.5;
  for (double phi : {5.0, 20.0}) {
    Sized s = size_shape(BRepPrimAPI_MakeSphere(r).Shape(), curvature_only(phi));
    const double expected = 2 * r * std::sin(phi * kPi / 360);
    for (int v = 0; v < s.bg.num_vertices(); ++v) {
      INFO("vertex " << v << " dim " << int(s.bg.dim[v]));
      CHECK(s.m.h_curvature[v] == Approx(expected).epsilon(0.01));
    }
  }
}

TEST_CASE("a deviation bound caps the curvature size: a triangle's centre on a sphere, a side's middle on a cylinder") {
  const double r = 2.5, delta = 0.01;
  SizingParams p = curvature_only(90.0);  // 2 r sin(45 deg) = 3.5: the deviation bound is the smaller
  p.deviation = delta;
  // On a sphere an equilateral triangle's centre is the furthest point off it:
  // (k1 + k2) h^2 / 12 = h^2 / (6 r), the height of the chord h on an arc of
  // radius 3 r / 4, so h = 2 sqrt(2 (3 r / 4) delta - delta^2) = 0.387.
  Sized s = size_shape(BRepPrimAPI_MakeSphere(r).Shape(), p);
  const double on_sphere = 2 * std::sqrt(1.5 * r * delta - delta * delta);
  for (int v = 0; v < s.bg.num_vertices(); ++v) CHECK(s.m.h_curvature[v] == Approx(on_sphere).epsilon(0.01));
  // On a cylinder the middle of a side across the axis is: the chord of height
  // delta on radius r, 0.447, at every vertex of the side (the caps are flat,
  // their circles have the side's curvature).
  Sized c = size_shape(BRepPrimAPI_MakeCylinder(r, 10.0).Shape(), p);
  const double on_cylinder = 2 * std::sqrt(2 * r * delta - delta * delta);
  int side = 0;
  for (int v = 0; v < c.bg.num_vertices(); ++v)
    if (std::abs(std::hypot(c.bg.xyz[v].x(), c.bg.xyz[v].y()) - r) < 1e-6) {
      ++side;
      CHECK(c.m.h_curvature[v] == Approx(on_cylinder).epsilon(0.01));
    }
  CHECK(side > 0);
  p.deviation = 0;  // none: back to 2 r sin(phi_c / 2)
  Sized off = size_shape(BRepPrimAPI_MakeSphere(r).Shape(), p);
  for (int v = 0; v < off.bg.num_vertices(); ++v)
    CHECK(off.m.h_curvature[v] == Approx(2 * r * std::sin(M_PI / 4)).epsilon(0.01));
}

TEST_CASE("with a deviation bound, radii of curvature under it set no curvature size and phi_c none under twice it") {
  // A sphere of radius 2.5 lies within 2.5 of any chord across it: a bound of
  // 3 asks for less accuracy than its curvature, so neither the bound nor
  // phi_c sizes it; a bound of 1 still does (phi_c's 2 r sin(45 deg) = 3.54
  // and the chord of height 1 on radius 3 r / 4, 3.32: the smaller).
  const double r = 2.5;
  SizingParams p = curvature_only(90.0);
  p.deviation = 3.0;
  Sized above = size_shape(BRepPrimAPI_MakeSphere(r).Shape(), p);
  for (int v = 0; v < above.bg.num_vertices(); ++v) CHECK(above.m.h_curvature[v] == kNoLimit);
  p.deviation = 1.0;
  Sized below = size_shape(BRepPrimAPI_MakeSphere(r).Shape(), p);
  const double expected = 2 * std::sqrt(2 * 0.75 * r * 1.0 - 1.0);
  for (int v = 0; v < below.bg.num_vertices(); ++v) CHECK(below.m.h_curvature[v] == Approx(expected).epsilon(0.01));
  // phi_c = 5 asks for 2 r sin(2.5 deg) = 0.22, but no finer than 2 delta: a
  // chord of 2 lies within 1 of this sphere, as of any arc of radius 1 or more.
  p.phi_c_deg = 5;
  Sized fine_angle = size_shape(BRepPrimAPI_MakeSphere(r).Shape(), p);
  for (int v = 0; v < fine_angle.bg.num_vertices(); ++v) CHECK(fine_angle.m.h_curvature[v] == Approx(2.0));
}

TEST_CASE("face proximity is the width across the face: a disc's diameter, not 2 A / l") {
  // A cylinder of radius 2 and height 20: its caps are discs 4 across (2A/l
  // would say 2), its side a band 20 wide.
  SizingParams p;
  p.local_proximity = false;
  p.h_min = 1e-6;
  p.h_max = 100;
  Sized s = size_shape(BRepPrimAPI_MakeCylinder(2.0, 20.0).Shape(), p);
  int rim = 0;
  for (int v = 0; v < s.bg.num_vertices(); ++v) {
    const double z = s.bg.xyz[v].z();
    if (s.bg.dim[v] == 2 || (std::abs(z) > 1e-9 && std::abs(z - 20) > 1e-9)) continue;  // on the caps' circles
    ++rim;
    // Across the cap through the axis: 4 (the chord of the tessellated circle
    // is a little shorter), over mu_d = 2.
    CHECK(s.m.h_proximity[v] == Approx(2.0).epsilon(0.01));
  }
  CHECK(rim > 20);
}

TEST_CASE("cylinder of radius r gives h_c = 2 r sin(phi_c / 2) on its side and no limit inside its flat caps") {
  const double r = 1.5;
  Sized s = size_shape(BRepPrimAPI_MakeCylinder(r, 4.0).Shape(), curvature_only(5.0));
  const double expected = 2 * r * std::sin(5.0 * M_PI / 360);
  int side = 0, cap_inside = 0;
  for (int v = 0; v < s.bg.num_vertices(); ++v) {
    const bool on_side = s.bg.dim[v] != 2 || s.model.face_period_u(s.bg.entity[v]) > 0;
    if (on_side) {
      ++side;
      CHECK(s.m.h_curvature[v] == Approx(expected).epsilon(0.01));
    } else {
      ++cap_inside;
      CHECK(s.m.h_curvature[v] == kNoLimit);
    }
  }
  CHECK(side > 0);
}

TEST_CASE("a box with one tiny edge grades away from it at exactly the bound") {
  // A quadrilateral prism whose profile has one edge of length 0.01.
  BRepBuilderAPI_MakePolygon profile;
  for (const gp_Pnt& q : {gp_Pnt(0, 0, 0), gp_Pnt(10, 0, 0), gp_Pnt(10, 10, 0), gp_Pnt(0.01, 10, 0), gp_Pnt(0, 10, 0)})
    profile.Add(q);
  profile.Close();
  TopoDS_Shape prism = BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(profile.Wire()).Face(), gp_Vec(0, 0, 10)).Shape();
  SizingParams p;
  p.local_proximity = false;
  p.h_min = 1e-4;
  p.h_max = 5;  // large enough that growth from the tiny face, not h_max, caps the big faces
  Sized s = size_shape(prism, p);
  REQUIRE(s.model.info().solids == 1);
  // The narrow side face along the tiny edge (0.01 x 10) sets the smallest
  // size: its width across, 0.01, over mu_d = 2.
  double h_tiny = kNoLimit;
  for (int v = 0; v < s.bg.num_vertices(); ++v) h_tiny = std::min(h_tiny, s.m.h_initial[v]);
  CHECK(h_tiny == Approx(0.01 / 2).epsilon(1e-9));
  // Edge stage alone: along every edge leaving the smallest size the growth is at
  // most ln(beta) l, and exactly that where no shorter path reaches the far end.
  std::vector<double> h = s.m.h_initial;
  smooth_edges(s.bg, s.m.edge_log_beta, h);
  int exact = 0;
  for (size_t e = 0; e < s.bg.edges.size(); ++e) {
    const int a = s.bg.edges[e][0], b = s.bg.edges[e][1];
    for (auto [lo, hi] : {std::make_pair(a, b), std::make_pair(b, a)}) {
      if (h[lo] != h_tiny || s.m.h_initial[hi] <= h_tiny + std::log(1.2) * (s.bg.xyz[a] - s.bg.xyz[b]).norm()) continue;
      const double bound = std::log(1.2) * (s.bg.xyz[a] - s.bg.xyz[b]).norm();
      CHECK(h[hi] - h[lo] <= bound * (1 + 1e-12));
      exact += std::abs(h[hi] - h[lo] - bound) <= 1e-9 * bound;
    }
  }
  CHECK(exact >= 3);
  smooth(s.bg, s.m);
  const GradationCheck c = check_gradation(s.bg, s.m);
  CHECK(c.max_edge_ratio <= 1 + 1e-9);
  // The bound is nearly reached, not just respected: the least-change
  // triangle correction lowers the middle corner of a triangle a little so
  // that its far corner keeps most of its size, which leaves the steepest
  // edges here 8% under their bound.
  CHECK(c.max_edge_ratio >= 0.9);
  CHECK(c.max_triangle_ratio <= 1 + 1e-9);
}

TEST_CASE("with a deviation bound, faces narrower and curves shorter than twice it set no proximity size") {
  // A 100 x 100 x 1 slab: four side faces 1 mm wide, four curves 1 mm long.
  // Without a bound the side faces give 1 / mu_d at their rims and the short
  // curves 1; a bound of 0.6 (2 x 0.6 > 1) asks for less accuracy than the
  // 1 mm features, so they set no size; a bound of 0.4 keeps them.
  Model m = model_from_shape(BRepPrimAPI_MakeBox(100.0, 100.0, 1.0).Shape());
  BackgroundMesh bg = build_background_mesh(m);
  SizingParams p;
  auto smallest = [&](const std::vector<double>& h) { return *std::min_element(h.begin(), h.end()); };
  // With a bound, a flat face wider than 2 delta gets one row of elements
  // across, twice its width long (more would not bring the mesh closer to the
  // plane), not mu_d: a size of 2.
  for (double delta : {0.0, 0.4, 0.6}) {
    p.deviation = delta;
    const std::vector<double> face = face_proximity_sizes(m, bg, p), curve = curve_length_sizes(m, bg, p);
    INFO("deviation " << delta);
    if (delta == 0) {
      CHECK(smallest(face) == Approx(1.0 / p.mu_d));
      CHECK(smallest(curve) == Approx(1.0));
    } else if (delta < 0.5) {
      CHECK(smallest(face) == Approx(2.0));
      CHECK(smallest(curve) == Approx(1.0));
      // Fewer elements across never means smaller sizes: one row for any
      // mu_d down to one half, mu_d itself below.
      for (double mu : {1.0, 0.75, 0.25}) {
        SizingParams q = p;
        q.mu_d = mu;
        INFO("mu_d " << mu);
        CHECK(smallest(face_proximity_sizes(m, bg, q)) == Approx(1.0 / std::min(mu, 0.5)));
      }
    } else {
      CHECK(smallest(face) == Approx(200.0));  // the big faces' own width still counts (twice: flat)
      CHECK(smallest(curve) == Approx(100.0));
    }
  }
}

TEST_CASE("with a deviation bound, a curved narrow face keeps mu_d elements across until one chord across it is within the bound") {
  // A box edge rounded with radius 2: the fillet is a quarter cylinder whose
  // width across (the chord, sqrt(2) r) is 2.83. A chord of height delta on
  // it is 2 sqrt(2 r delta - delta^2): 1.25 at delta = 0.1, under the width,
  // so the fillet keeps mu_d = 2 elements across (1.41); 3.46 at delta = 1,
  // over it, so one row of elements across, twice the width long (5.66), is
  // as close to the surface. The rounded edge is one 100 long, so that the
  // fillet's width along itself (100 / mu_d) and the end faces' (10 wide) set
  // larger sizes.
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(100.0, 100.0, 10.0).Shape();
  BRepFilletAPI_MakeFillet fillet(box);
  for (TopExp_Explorer ex(box, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
    if (BRep_Tool::Pnt(TopExp::FirstVertex(e)).Distance(BRep_Tool::Pnt(TopExp::LastVertex(e))) > 99) {
      fillet.Add(2.0, e);
      break;
    }
  }
  Model m = model_from_shape(fillet.Shape());
  BackgroundMesh bg = build_background_mesh(m);
  int cylinder = 0;  // the fillet: pi r / 2 times 100, the smallest face
  for (int f = 1; f <= m.num_faces(); ++f)
    if (cylinder == 0 || m.face_area(f) < m.face_area(cylinder)) cylinder = f;
  REQUIRE(m.face_area(cylinder) == Approx(M_PI * 100).epsilon(0.01));
  const double width = std::sqrt(2.0) * 2.0;  // the chord across a quarter circle of radius 2
  SizingParams p;
  auto on_fillet = [&](const std::vector<double>& h) {
    double least = kNoLimit;
    for (int v : bg.patches[cylinder - 1].vertex) least = std::min(least, h[v]);
    return least;
  };
  for (double delta : {0.0, 0.1, 1.0}) {
    p.deviation = delta;
    INFO("deviation " << delta);
    const double h = on_fillet(face_proximity_sizes(m, bg, p));
    if (delta < 0.5) CHECK(h == Approx(width / p.mu_d).epsilon(0.02));
    else CHECK(h == Approx(2 * width).epsilon(0.02));
  }
}

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

TEST_CASE("smoothed map meets the edge and triangle bounds on every shared model, lowering only, never below h_min") {
  for (const auto& sm : test::shared_models()) {
    SECTION(sm.file) {
      const auto run = test::run_until(test::run_options(sm.file), "smoothing");  // the command's stages
      const BackgroundMesh& bg = run->bg;
      const SizeMap& m = run->sizes;
      const GradationCheck c = check_gradation(bg, m);
      CHECK(c.max_edge_ratio <= 1 + 1e-9);
      CHECK(c.max_triangle_ratio <= 1 + 1e-9);
      for (int v = 0; v < bg.num_vertices(); ++v) {
        CHECK(m.h[v] <= m.h_initial[v]);
        CHECK(m.h[v] >= m.h_min * (1 - 1e-12));
        CHECK(m.h_initial[v] <= m.h_max);
        CHECK(std::isfinite(m.h[v]));
      }
    }
  }
}

TEST_CASE("lp_solve and the exact solver give the same edge-stage sizes to 1e-9") {
  for (const char* file : {"onera_m6_wing.stp", "cylinder_head_fins.stp"}) {
    Model model = load_model(test::model_path(file));
    BackgroundMesh bg = build_background_mesh(model);
    SizeMap m = initial_sizes(model, bg, SizingParams{}, model.info().diagonal());
    std::vector<double> exact = m.h_initial, lp = m.h_initial;
    smooth_edges(bg, m.edge_log_beta, exact);
    smooth_edges_lp(bg, m.edge_log_beta, lp);
    double worst = 0;
    for (int v = 0; v < bg.num_vertices(); ++v) worst = std::max(worst, std::abs(exact[v] - lp[v]) / exact[v]);
    INFO(file);
    CHECK(worst <= 1e-9);
  }
}

TEST_CASE("per-face beta and prescribed sizes take effect where set and nowhere else") {
  SizingParams p;
  p.local_proximity = false;
  p.face_beta[1] = 1.5;
  p.face_size[2] = UserSize{0.05, ""};
  p.curve_size[5] = UserSize{0, "0.02 + 0.001 * x"};
  p.point_size[7] = UserSize{0.01, ""};
  Sized s = size_shape(BRepPrimAPI_MakeBox(2.0, 3.0, 4.0).Shape(), p);
  // beta: a triangle of face 1 has ln 1.5; an edge inside face 1 too; an edge on its boundary takes ln 1.2.
  for (int t = 0; t < s.bg.num_triangles(); ++t)
    CHECK(s.m.tri_log_beta[t] == Approx(std::log(s.bg.tri_face[t] == 1 ? 1.5 : 1.2)));
  for (size_t e = 0; e < s.bg.edges.size(); ++e) {
    const int a = s.bg.edges[e][0];
    const bool inside_face1 = s.bg.edge_curve[e] == 0 && s.bg.dim[a] == 2 && s.bg.entity[a] == 1;
    const bool inside_other = s.bg.edge_curve[e] == 0 && s.bg.dim[a] == 2 && s.bg.entity[a] != 1;
    if (inside_face1) CHECK(s.m.edge_log_beta[e] == Approx(std::log(1.5)));
    if (inside_other || s.bg.edge_curve[e] != 0) CHECK(s.m.edge_log_beta[e] == Approx(std::log(1.2)));
  }
  // Prescribed sizes: exactly the vertices on face 2, on curve 5 (with its end points) and point 7.
  const auto& face2 = s.bg.patches[1].vertex;
  for (int v = 0; v < s.bg.num_vertices(); ++v) {
    const bool on_face2 = std::find(face2.begin(), face2.end(), v) != face2.end();
    const bool on_curve5 = (s.bg.dim[v] == 1 && s.bg.entity[v] == 5) ||
                           v == s.model.curve_start_point(5) - 1 || v == s.model.curve_end_point(5) - 1;
    double expected = kNoLimit;
    if (on_face2) expected = std::min(expected, 0.05);
    if (on_curve5) expected = std::min(expected, 0.02 + 0.001 * s.bg.xyz[v].x());
    if (v == 6) expected = std::min(expected, 0.01);
    INFO("vertex " << v);
    if (expected == kNoLimit) CHECK(s.m.h_user[v] == kNoLimit);
    else CHECK(s.m.h_user[v] == Approx(expected).epsilon(1e-12));
  }
}

TEST_CASE("bad sizing parameters give one clear error and a non-zero exit") {
  const std::string wing = test::model_path("onera_m6_wing.stp");
  const std::string dir = std::filesystem::temp_directory_path().string() + "/sizemesh_cfg_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  auto config = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
    return dir + "/" + name;
  };
  auto expect_error = [&](const std::string& args, const std::string& words) {
    const auto r = test::run_sizemesh(wing + " -q " + args);
    INFO(args << " -> " << r.err);
    CHECK(r.status == 1);
    CHECK(r.err_lines() == 1);
    CHECK(r.err.find(words) != std::string::npos);
  };
  expect_error("--beta 0.9", "beta must be at least 1");
  expect_error("--phi-c 0", "phi_c must be in (0, 180)");
  expect_error("--phi-c 180", "phi_c must be in (0, 180)");
  expect_error("--mu-d 0", "mu_d must be positive");
  expect_error("--mu-d -2", "mu_d must be positive");
  expect_error("--h-min 10 --h-max 1", "is larger than h_max");
  expect_error("--deviation -1", "deviation must be zero (none) or positive");
  expect_error("--config " + config("dev.json", R"({"deviation": "fine"})"), "deviation must be a number");
  expect_error("--config " + config("side.json", R"({"gap_side": "sideways"})"), "gap_side must be one of auto, fluid, solid, both");
  expect_error("--config " + config("side2.json", R"({"gap_side": 1})"), "gap_side must be a string");
  CHECK(test::run_sizemesh(wing + " -q --gap-side sideways").status == 2);
  expect_error("--config " + config("id.json", R"({"face_size": {"99": 1.0}})"), "names face 99 but the model has 11");
  expect_error("--config " + config("expr.json", R"({"face_size": {"1": "2 * (x + "}})"), "malformed size expression");
  expect_error("--config " + config("neg.json", R"({"face_size": {"1": "x - 1e9"}})"), "sizes must be positive");
  expect_error("--config " + config("json.json", R"({"beta": 1.2,, })"), "not valid JSON");
  expect_error("--config " + config("key.json", R"({"betta": 1.2})"), "unknown key 'betta'");
  expect_error("--config " + config("beta.json", R"({"face_beta": {"2": 0.5}})"), "face 2: beta must be at least 1");
  expect_error("--config " + dir + "/missing.json", "cannot read config file");
  std::filesystem::remove_all(dir);
}

TEST_CASE("the example config is accepted and its local sizes reach the background fields") {
  const std::string out = std::filesystem::temp_directory_path().string() + "/sizemesh_cfg_bg_" +
                          std::to_string(::getpid()) + ".vtu";
  const auto r = test::run_sizemesh(std::string(SIZEMESH_EXAMPLES_DIR) + "/onera_m6_wing.stp -q --config " +
                                    SIZEMESH_EXAMPLES_DIR + "/sizing.json --background " + out);
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string vtu = test::slurp(out);
  for (const char* field : {"h_curvature", "h_proximity", "h_user", "h_initial", "h_smoothed", "gradient_ratio"})
    CHECK(vtu.find(field) != std::string::npos);
  std::filesystem::remove(out);
}
