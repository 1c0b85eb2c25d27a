// Face repairs in preparation: a strip narrower than a width becomes a curve, faces split where they fold or jump.
#include <catch2/catch.hpp>

// GCC takes NCollection_Array2's row table, indexed from its lower bound, for out of bounds once inlined.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#pragma GCC diagnostic pop
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>

#include <cmath>
#include <utility>
#include <vector>

#include "cad/occt_model.h"
#include "core/size_field.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "tests/prepare_checks.h"
#include "tests/test_models.h"

using namespace sizemesh;
using test::mesh_closed;

namespace {

// A unit-wide strip in the plane y = 0..1 made of two cubic Bezier spans in
// u joined at a triple knot u = 1 (C0 in its parametrisation): the first span
// runs from x = 0 to 1 along +x; the second continues to `end` from there,
// reached with `speed` times the first span's parametric speed.
TopoDS_Shape two_span_strip(const gp_Vec& second, double speed) {
  TColgp_Array2OfPnt poles(1, 7, 1, 2);
  const gp_Vec first(1, 0, 0);
  for (int j = 1; j <= 2; ++j) {
    const gp_Vec y(0, j - 1, 0);
    for (int i = 0; i <= 3; ++i) poles(i + 1, j) = gp_Pnt(0, 0, 0).Translated(first * (i / 3.0) + y);
    for (int i = 1; i <= 3; ++i) poles(i + 4, j) = gp_Pnt(1, 0, 0).Translated(second * (speed * i / 3.0) + y);
  }
  TColStd_Array1OfReal uk(1, 3), vk(1, 2);
  TColStd_Array1OfInteger um(1, 3), vm(1, 2);
  uk(1) = 0, uk(2) = 1, uk(3) = 2;
  um(1) = 4, um(2) = 3, um(3) = 4;
  vk(1) = 0, vk(2) = 1;
  vm(1) = 2, vm(2) = 2;
  Handle(Geom_BSplineSurface) s = new Geom_BSplineSurface(poles, uk, vk, um, vm, 3, 1);
  return BRepBuilderAPI_MakeFace(s, 1e-7).Shape();
}

}  // namespace

TEST_CASE("a strip narrower than the width given becomes one curve shared by the faces either side") {
  // A tapered plate, 1 deep, chord 1 from a leading edge 0.1 thick to a blunt
  // trailing edge 1e-4 thick: the trailing edge is a strip 1 x 1e-4.
  const double te = 1e-4;
  const gp_Pnt a(0, 0.05, 0), b(1, te / 2, 0), c(1, -te / 2, 0), d(0, -0.05, 0);
  const TopoDS_Shape profile = BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakePolygon(a, b, c, d, true).Wire()).Face();
  const TopoDS_Shape plate = BRepPrimAPI_MakePrism(profile, gp_Vec(0, 0, 1)).Shape();
  REQUIRE(count_free_curves(plate) == 0);
  std::vector<std::pair<TopoDS_Face, TopoDS_Face>> replaced;
  auto follow = [&](const TopoDS_Face& from, const TopoDS_Face& to) { replaced.emplace_back(from, to); };
  int collapsed = 0;
  // Wider strips than the width stay.
  CHECK(collapse_strips(plate, te / 2, follow, collapsed).IsSame(plate));
  CHECK(collapsed == 0);
  const TopoDS_Shape thin = collapse_strips(plate, 2 * te, follow, collapsed);
  CHECK(collapsed == 1);
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(thin, TopAbs_FACE, faces);
  CHECK(faces.Extent() == 5);
  CHECK(count_free_curves(thin) == 0);
  CHECK(BRepCheck_Analyzer(thin).IsValid());
  // The two skins, the two end caps: the faces beside the strip, rebuilt.
  CHECK(replaced.size() == 4);
  // One closed surface meshes, its area the plate's less the strip's.
  const Model model = model_from_shape(thin);
  const SurfaceMesh m = mesh_closed(model, 0.05);
  double area = 0;
  for (const auto& t : m.tris) area += 0.5 * (m.xyz[t[1]] - m.xyz[t[0]]).cross(m.xyz[t[2]] - m.xyz[t[0]]).norm();
  const double skin = std::hypot(1.0, 0.05 - te / 2), cap = 0.5 * (0.1 + te);
  CHECK(area == Approx(2 * skin + 2 * cap + 0.1).epsilon(1e-3));
}

TEST_CASE("faces split along knot lines where the surface folds or its parametrisation jumps", "[prepare]") {
  struct Case {
    const char* name;
    gp_Vec second;
    double speed;
    int faces;
  };
  const double c = std::cos(2 * kPi / 3), s = std::sin(2 * kPi / 3);
  for (const Case& k : {Case{"smooth: same direction, same speed", gp_Vec(1, 0, 0), 1.0, 1},
                        Case{"jump: same direction, five times the speed", gp_Vec(1, 0, 0), 5.0, 2},
                        Case{"crease: turned by 120 degrees", gp_Vec(c, 0, s), 1.0, 2},
                        Case{"mild turn: 10 degrees", gp_Vec(std::cos(0.17), 0, std::sin(0.17)), 1.0, 1}}) {
    SECTION(k.name) {
      const Model model = model_from_shape(two_span_strip(k.second, k.speed));
      REQUIRE(model.num_faces() == k.faces);
      CHECK(model.info().preparation.faces_split_at_folds == (k.faces > 1 ? 1 : 0));
      const double length = 1 + k.second.Magnitude() * k.speed;
      double area = 0;
      for (int f = 1; f <= model.num_faces(); ++f) {
        CHECK(model.source_face(f) == 1);
        area += model.face_area(f);
      }
      CHECK(area == Approx(length).epsilon(1e-6));
      // The knot line is a curve: the mesh has nodes on it, at x = 1 in the
      // first span's end plane, and no triangle crosses it.
      const UniformSize h(0.1);
      const SurfaceMesh m = mesh_surface(model, h);
      const MeshQuality q = mesh_quality(m, model, h);
      REQUIRE(m.failures.empty());
      CHECK(q.inverted == 0);
      CHECK(q.below_12 == 0);
      if (k.faces > 1) {
        int on_line = 0;
        for (size_t i = 0; i < m.xyz.size(); ++i)
          on_line += m.node_dim[i] <= 1 && std::abs(m.xyz[i].x() - 1) < 1e-9 && std::abs(m.xyz[i].z()) < 1e-9;
        CHECK(on_line >= 11);  // the line y = 0..1 at h = 0.1, ends included
      }
    }
  }
  // The manta's pods fold over at knots and its body patches change speed
  // across them: the preparation splits them, and the split pieces keep
  // their source face ids.
  const Model manta = load_model(test::model_path("manta2_openvsp.stp"));
  CHECK(manta.info().preparation.faces_split_at_folds > 0);
  for (int f = 1; f <= manta.num_faces(); ++f) CHECK(manta.source_face(f) >= 1);
}
