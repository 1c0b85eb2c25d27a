// Background mesh (paper 3.1): classification, merging, uv, watertightness, area.
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <STEPControl_Writer.hxx>

#include <fstream>
#include <sstream>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>

#include "background/background_mesh.h"
#include "cad/occt_model.h"
#include "tests/background_checks.h"
#include "tests/test_models.h"

using namespace sizemesh;

namespace {

double cad_area(const Model& m) {
  double a = 0;
  for (int f = 1; f <= m.num_faces(); ++f) a += m.face_area(f);
  return a;
}

// Every face has triangles; closed: every edge in two triangles; area within 1%.
void check_mesh(const Model& model, const BackgroundMesh& bg, bool closed) {
  REQUIRE(static_cast<int>(bg.patches.size()) == model.num_faces());
  for (const FacePatch& p : bg.patches) {
    INFO("face " << p.face);
    CHECK(!p.tris.empty());
    CHECK(p.adj.size() == p.tris.size());
  }
  const double a_cad = cad_area(model), a_bg = bg.area();
  CHECK(std::abs(a_bg - a_cad) <= 0.01 * a_cad);
  if (closed) CHECK(test::open_background_edges(model, bg) == 0);
  // Classification: dim-0 vertices are the B-rep points, in id order.
  for (int p = 0; p < model.num_points(); ++p) {
    CHECK(bg.dim[p] == 0);
    CHECK(bg.entity[p] == p + 1);
  }
  for (int v = model.num_points(); v < bg.num_vertices(); ++v) CHECK(bg.dim[v] > 0);
  // Mesh edges on curves join vertices classified on that curve or its end points.
  for (size_t e = 0; e < bg.edges.size(); ++e) {
    const int c = bg.edge_curve[e];
    if (c == 0) continue;
    for (int v : bg.edges[e]) {
      const bool ok = (bg.dim[v] == 1 && bg.entity[v] == c) ||
                      (bg.dim[v] == 0 && (bg.entity[v] == model.curve_start_point(c) ||
                                          bg.entity[v] == model.curve_end_point(c)));
      CHECK(ok);
    }
  }
}

// The surface at every stored uv lands on the vertex within the tessellation
// tolerance (curve vertices: plus the curve's distance to the surface).
double worst_uv_error(const Model& model, const BackgroundMesh& bg) {
  double worst = 0;
  for (const FacePatch& p : bg.patches)
    for (size_t l = 0; l < p.uv.size(); ++l)
      worst = std::max(worst, (model.eval_face(p.face, p.uv[l]).p - bg.xyz[p.vertex[l]]).norm());
  return worst;
}

}  // namespace

TEST_CASE("background mesh of every shared model is complete, classified and close to the CAD surface") {
  for (const auto& sm : test::shared_models()) {
    SECTION(sm.file) {
      Model model = load_model(test::model_path(sm.file));
      BackgroundOptions opt;
      BackgroundMesh bg = build_background_mesh(model, opt);
      check_mesh(model, bg, sm.closed);
      CHECK(worst_uv_error(model, bg) <= 2 * opt.deflection_rel * model.info().diagonal());
      // uses: each vertex knows its uv on every face it lies on
      for (int v = 0; v < bg.num_vertices(); ++v) CHECK(bg.use_start[v + 1] > bg.use_start[v]);
    }
  }
}

TEST_CASE("closed shared models are watertight after loading") {
  for (const auto& sm : test::shared_models()) {
    if (!sm.closed) continue;
    Model model = load_model(test::model_path(sm.file));
    INFO(sm.file);
    CHECK(model.info().free_curves_after_sewing == 0);
  }
}

TEST_CASE("sewing joins the unsewn F-16 patches") {
  Model raw = load_model(test::model_path("f16_openvsp.stp"), test::load_options(false, true));
  Model sewn = load_model(test::model_path("f16_openvsp.stp"));
  CHECK(raw.info().free_curves_after_sewing == raw.info().free_curves_before_sewing);
  CHECK(raw.info().faces + raw.info().zero_area_faces_removed == 105);
  CHECK(raw.info().zero_area_faces_removed == 36);
  CHECK(sewn.info().free_curves_before_sewing == raw.info().free_curves_before_sewing);
  CHECK(sewn.info().free_curves_after_sewing < raw.info().free_curves_after_sewing / 4);
  CHECK(sewn.info().unit == "ft");
}

TEST_CASE("ids are stable across two loads of the same file") {
  for (const char* file : {"steering_knuckle.stp", "d150_fuselage.igs", "f16_openvsp.stp"}) {  // F-16: after the union
    Model a = load_model(test::model_path(file)), b = load_model(test::model_path(file));
    REQUIRE(a.num_faces() == b.num_faces());
    REQUIRE(a.num_curves() == b.num_curves());
    REQUIRE(a.num_points() == b.num_points());
    for (int f = 1; f <= a.num_faces(); ++f) CHECK(a.face_area(f) == b.face_area(f));
    for (int c = 1; c <= a.num_curves(); ++c) CHECK(a.curve_length(c) == b.curve_length(c));
    for (int p = 1; p <= a.num_points(); ++p) CHECK(a.point_xyz(p) == b.point_xyz(p));
  }
}

TEST_CASE("file units and entity counts are reported as the file states them") {
  Model wing = load_model(test::model_path("onera_m6_wing.stp"));
  CHECK(wing.info().unit == "mm");
  CHECK(wing.info().format == "STEP");
  CHECK(wing.info().solids == 1);
  CHECK(wing.info().faces == 11);
  CHECK(wing.info().curves == 21);
  CHECK(wing.info().bbox_max.y() == Approx(1218.47).epsilon(1e-4));  // semispan in mm, not converted
  Model fuselage = load_model(test::model_path("d150_fuselage.igs"));
  CHECK(fuselage.info().unit == "mm");
  CHECK(fuselage.info().format == "IGES");
  CHECK(fuselage.info().faces == 238);
}

TEST_CASE("analytic solids: box, sphere, cylinder, torus and a plate with a hole") {
  SECTION("box: 8 points, 12 curves, 6 faces, every curve shared by two faces") {
    Model m = model_from_shape(BRepPrimAPI_MakeBox(2.0, 3.0, 4.0).Shape());
    BackgroundMesh bg = build_background_mesh(m);
    check_mesh(m, bg, true);
    CHECK(m.num_points() == 8);
    CHECK(m.num_curves() == 12);
    CHECK(bg.area() == Approx(2 * (6 + 8 + 12)).epsilon(1e-9));
    int on_curves = 0;
    for (int c : bg.edge_curve) on_curves += c != 0;
    CHECK(on_curves >= 12);
  }
  SECTION("sphere: poles and seam, seam vertices carry two uvs on the same face") {
    Model m = model_from_shape(BRepPrimAPI_MakeSphere(1.5).Shape());
    BackgroundMesh bg = build_background_mesh(m);
    check_mesh(m, bg, true);
    CHECK(worst_uv_error(m, bg) < 1e-9);
    int two_uvs = 0;
    for (int v = 0; v < bg.num_vertices(); ++v)
      if (bg.use_start[v + 1] - bg.use_start[v] >= 2) ++two_uvs;
    CHECK(two_uvs >= 3);
  }
  SECTION("cylinder") {
    Model m = model_from_shape(BRepPrimAPI_MakeCylinder(1.0, 3.0).Shape());
    BackgroundMesh bg = build_background_mesh(m);
    check_mesh(m, bg, true);
    CHECK(worst_uv_error(m, bg) < 1e-9);
  }
  SECTION("torus") {
    Model m = model_from_shape(BRepPrimAPI_MakeTorus(3.0, 1.0).Shape());
    check_mesh(m, build_background_mesh(m), true);
  }
  SECTION("plate with a hole") {
    TopoDS_Shape plate = BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(10.0, 10.0, 1.0).Shape(),
                                         BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(5, 5, -1), gp_Dir(0, 0, 1)), 2.0, 3.0).Shape())
                             .Shape();
    Model m = model_from_shape(plate);
    BackgroundMesh bg = build_background_mesh(m);
    check_mesh(m, bg, true);
    int faces_with_hole = 0;
    for (int f = 1; f <= m.num_faces(); ++f) faces_with_hole += m.face_loops(f).size() == 2;
    CHECK(faces_with_hole == 2);
  }
}

TEST_CASE("face names from a STEP file are kept with their ids") {
  // A box written by OpenCASCADE's STEP writer, one face renamed in the text.
  const std::string path = "/tmp/sizemesh_named_" + std::to_string(::getpid()) + ".step";
  STEPControl_Writer writer;
  writer.Transfer(BRepPrimAPI_MakeBox(1.0, 2.0, 3.0).Shape(), STEPControl_AsIs);
  REQUIRE(writer.Write(path.c_str()) == IFSelect_RetDone);
  std::string text;
  {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    text = s.str();
  }
  const size_t at = text.find("ADVANCED_FACE('");
  REQUIRE(at != std::string::npos);
  text.insert(at + std::string("ADVANCED_FACE('").size(), "inlet");
  std::ofstream(path) << text;
  Model m = load_model(path);
  int named = 0;
  for (int f = 1; f <= m.num_faces(); ++f)
    if (!m.face_name(f).empty()) {
      ++named;
      CHECK(m.face_name(f) == "inlet");
    }
  CHECK(named == 1);
  std::remove(path.c_str());
}
