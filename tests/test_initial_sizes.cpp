// Initial sizes on analytic shapes (paper 3.2): curvature sizes, the deviation bound's chords, widths across faces.
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Tool.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <vector>

#include "cad/occt_model.h"
#include "sizing/initial_sizes.h"
#include "sizing/proximity_size.h"
#include "tests/sizing_checks.h"

using namespace sizemesh;
using test::Sized;
using test::size_shape;

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
