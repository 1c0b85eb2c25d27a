// Preparing built solids: a wing through a fuselage and touching boxes unite, an inner plane goes, face ids follow.
#include <catch2/catch.hpp>

#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Ax2.hxx>

#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "cad/occt_model.h"
#include "sizing/params.h"
#include "tests/prepare_checks.h"
#include "tests/test_models.h"

using namespace sizemesh;
using test::compound;
using test::mesh_closed;
using test::quad;
using test::total_area;

namespace {

double signed_volume(const SurfaceMesh& m) {
  double v = 0;
  for (const auto& t : m.tris) v += m.xyz[t[0]].dot(m.xyz[t[1]].cross(m.xyz[t[2]])) / 6.0;
  return v;
}

}  // namespace

TEST_CASE("a box wing through a cylinder fuselage unites into one closed surface of the analytic area") {
  // Fuselage: radius 1 along x from 0 to 10. Wing: chord 2 (x 3..5), span 12
  // (y -6..6), thickness 0.4 (z -0.2..0.2).
  const TopoDS_Shape fuselage = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)), 1.0, 10.0).Shape();
  const TopoDS_Shape wing = BRepPrimAPI_MakeBox(gp_Pnt(3, -6, -0.2), 2.0, 12.0, 0.4).Shape();
  const Model model = model_from_shape(compound({fuselage, wing}));
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 2);
  CHECK(p.fused);
  CHECK(p.solids_fused == 2);
  CHECK(model.closed());
  CHECK(model.info().solids == 1);
  // Cylinder side with two holes, two caps; wing top, bottom, front and back
  // each cut in two by the fuselage, two tips.
  CHECK(model.num_faces() == 13);

  // Exact wetted area: the cylinder without the two strips |z| < 0.2 under
  // the wing, plus the box without what lies inside the cylinder.
  const double s = 0.2, c = std::sqrt(1 - s * s);
  const double cylinder = 2 * kPi * 10 + 2 * kPi - 2 * 2 * (2 * std::asin(s));
  const double box = 2 * (2 * 12 + 2 * 0.4 + 12 * 0.4) - 2 * (2 * 2 * c) - 2 * 2 * (s * c + std::asin(s));
  CHECK(total_area(model) == Approx(cylinder + box).epsilon(1e-3));

  // Junction curves: shared by a face from the fuselage and one from the wing
  // (the sewn ids: the cylinder's three faces come first), four a side.
  std::map<int, std::set<bool>> curve_sides;
  for (int f = 1; f <= model.num_faces(); ++f) {
    const int src = model.source_face(f);
    REQUIRE(src >= 1);
    REQUIRE(src <= 9);
    for (const auto& loop : model.face_loops(f))
      for (const auto& use : loop) curve_sides[use.curve].insert(src <= 3);
  }
  int junctions = 0;
  for (const auto& [curve, sides] : curve_sides) junctions += sides.size() == 2;
  CHECK(junctions == 8);

  const SurfaceMesh m = mesh_closed(model, 0.1);
  const double volume = kPi * 10 + 2 * 12 * 0.4 - 2 * 2 * (s * c + std::asin(s));
  CHECK(signed_volume(m) == Approx(volume).epsilon(5e-3));  // outward, polygonal
}

TEST_CASE("config face ids keep addressing the faces as sewn after the union") {
  const Model model = model_from_shape(compound({BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 1.0, 1.0, 1.0).Shape(),
                                                 BRepPrimAPI_MakeBox(gp_Pnt(1, 0, 0), 1.0, 1.0, 1.0).Shape()}));
  std::vector<int> source;
  for (int f = 1; f <= model.num_faces(); ++f) source.push_back(model.source_face(f));
  REQUIRE(model.info().sewn_faces == 12);
  SizingParams p;
  for (int id = 1; id <= 12; ++id) p.face_size[id] = UserSize{0.01 * id, ""};
  p.face_beta[3] = 1.5;
  remap_face_ids(p, source, 12);
  REQUIRE(p.face_size.size() == 10);  // one entry per result face
  for (int f = 1; f <= model.num_faces(); ++f) CHECK(p.face_size.at(f).value == Approx(0.01 * model.source_face(f)));
  for (const auto& [f, beta] : p.face_beta) CHECK(model.source_face(f) == 3);
  SizingParams bad;
  bad.face_mu_d[13] = 2;
  CHECK_THROWS_WITH(remap_face_ids(bad, source, 12), "config names face 13 but the model has 12 faces");
}

TEST_CASE("two touching boxes give one closed surface with no internal face") {
  const Model model = model_from_shape(compound({BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 1.0, 1.0, 1.0).Shape(),
                                                 BRepPrimAPI_MakeBox(gp_Pnt(1, 0, 0), 1.0, 1.0, 1.0).Shape()}));
  // Face to face, the two are repaired as one body: the faces at x = 1 go.
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 2);
  CHECK(p.components[0].faces_removed == 2);
  CHECK(p.components[1].route.rfind("one body with component 1 (faces back to back)", 0) == 0);
  CHECK(model.closed());
  CHECK(model.num_faces() == 10);  // two ends, four sides in two pieces each
  CHECK(total_area(model) == Approx(10.0).epsilon(1e-12));
  const SurfaceMesh m = mesh_closed(model, 0.2);
  CHECK(signed_volume(m) == Approx(2.0).epsilon(1e-9));
  for (const auto& t : m.tris) {
    const bool on_contact = std::abs(m.xyz[t[0]].x() - 1) < 1e-9 && std::abs(m.xyz[t[1]].x() - 1) < 1e-9 &&
                            std::abs(m.xyz[t[2]].x() - 1) < 1e-9;
    CHECK_FALSE(on_contact);
  }
  const Model raw = model_from_shape(compound({BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 1.0, 1.0, 1.0).Shape(),
                                               BRepPrimAPI_MakeBox(gp_Pnt(1, 0, 0), 1.0, 1.0, 1.0).Shape()}),
                                     test::load_options(true, false));
  CHECK(raw.num_faces() == 12);
  CHECK_FALSE(raw.info().preparation.fused);
}

TEST_CASE("an internal planform plane between two open wing halves is taken out and the wing closes") {
  // Upper half: z 0..0.2 without its bottom; lower half: z -0.2..0 without
  // its top; the plane z = 0 shares their edges, so each is used three times.
  const double X = 2, Y = 6, t = 0.2;
  std::vector<TopoDS_Shape> faces;
  for (double z : {t, -t}) {
    faces.push_back(quad({0, 0, z}, {X, 0, z}, {X, Y, z}, {0, Y, z}));
    faces.push_back(quad({0, 0, 0}, {X, 0, 0}, {X, 0, z}, {0, 0, z}));
    faces.push_back(quad({0, Y, 0}, {X, Y, 0}, {X, Y, z}, {0, Y, z}));
    faces.push_back(quad({0, 0, 0}, {0, Y, 0}, {0, Y, z}, {0, 0, z}));
    faces.push_back(quad({X, 0, 0}, {X, Y, 0}, {X, Y, z}, {X, 0, z}));
  }
  faces.push_back(quad({0, 0, 0}, {X, 0, 0}, {X, Y, 0}, {0, Y, 0}));
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  for (const auto& f : faces) b.Add(c, f);

  const Model raw = model_from_shape(c, test::load_options(true, false));
  CHECK_FALSE(raw.closed());
  const Model model = model_from_shape(c);
  const Preparation& p = model.info().preparation;
  CHECK(p.internal_faces_removed == 1);
  CHECK(p.components_repaired == 1);
  CHECK(model.closed());
  CHECK(model.num_faces() == 10);
  CHECK(total_area(model) == Approx(2 * (X * Y + X * 2 * t + Y * 2 * t)).epsilon(1e-12));
  const SurfaceMesh m = mesh_closed(model, 0.1);
  CHECK(signed_volume(m) == Approx(X * Y * 2 * t).epsilon(1e-9));
}

TEST_CASE("a closed solid passes through the preparation unchanged") {
  const Model model = model_from_shape(BRepPrimAPI_MakeCylinder(1.0, 2.0).Shape());
  const Preparation& p = model.info().preparation;
  REQUIRE(p.components.size() == 1);
  CHECK(p.components[0].closed);
  CHECK(p.components[0].role == "solid");
  CHECK_FALSE(p.fused);
  CHECK(p.fallback.empty());
  CHECK(model.num_faces() == 3);
  for (int f = 1; f <= 3; ++f) CHECK(model.source_face(f) == f);
}
