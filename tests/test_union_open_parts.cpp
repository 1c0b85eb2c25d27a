// Open parts in the union: a slit wing closes, a sheet or disk inside a body is left out, an open tube is capped.
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <catch2/catch.hpp>
#include <gp_Ax2.hxx>
#include <gp_Ax3.hxx>
#include <gp_Circ.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>

#include <string>
#include <vector>

#include "cad/model.h"
#include "tests/brep_file.h"
#include "tests/cli_runner.h"
#include "tests/temp_dir.h"
#include "tests/test_models.h"
#include "tests/union_checks.h"

using namespace sizemesh;
using test::check_one_closed_surface;

TEST_CASE("a wing whose tips are slits and that carries its planform plane closes into one solid") {
  // OpenVSP's blunt-trailing-edge half wing: one skin face pinched to a line
  // at root and tip (two coincident edges each, which sewing cannot join),
  // and a planform plane inside, sewn to one side of the tip slit. The skin
  // is split between its slit edges, the halves sew, the plane is taken out.
  // Each half's root and tip caps collapse onto the chord, and over an area
  // where the blunt trailing edge meets them: they are split off the skin,
  // put on their planes, and the two halves of each cap merged. The blunt
  // trailing edge's base splits off each half at its crease (the spline's
  // C0 knot line, 90 degrees): root cap, tip cap, two skins, two base halves.
  const Model m = load_model(test::model_path("wing_blunt_te_openvsp.stp"));
  const Preparation& p = m.info().preparation;
  REQUIRE(p.components.size() == 1);
  CHECK(p.components[0].role == "solid");
  CHECK(p.internal_faces_removed == 1);
  CHECK(m.closed());
  CHECK(p.faces_made_planar == 4);
  CHECK(m.num_faces() == 6);
  CHECK(m.info().solids == 1);
  CHECK(p.half_model_axis == -1);
}

TEST_CASE("an open sheet inside a body is left out: the box alone, closed, exit 0") {
  // A box 2 x 1 x 1 with a plane across its inside at mid-height, reaching
  // its four side walls, as a wing's planform plane lies between its skins
  // (OpenVSP writes it as a component of its own).
  const test::TempDir dir("inner_sheet");
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(2, 1, 1).Shape();
  const TopoDS_Shape plane = BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, 0.5), gp_Dir(0, 0, 1)), 0, 2, 0, 1).Face();
  const std::string path = test::write_compound({box, plane}, dir / "inner.brep");
  const std::string args = path + " -q --h-max 0.2 -o " + (dir / "i.vtu");
  const auto j = test::run_with_report(args, dir / "r.json", 0);
  const auto& prep = j["preparation"];
  REQUIRE(prep["components"].size() == 2);
  CHECK(prep["internal_sheets"].get<std::vector<int>>() == std::vector<int>{2});
  CHECK(prep["components"][1]["role"] == "internal");
  CHECK(prep["components"][1]["route"] == "left out: a sheet inside a body");
  check_one_closed_surface(j["mesh"]);
  CHECK(j["mesh"]["area"].get<double>() == Approx(10.0).epsilon(1e-9));
  const auto r = test::run_sizemesh(args);
  CHECK(r.status == 0);
  CHECK(r.err.find("component 2 is an open sheet inside a body (an internal plane): no wall, left out of the "
                   "wetted surface") != std::string::npos);
}

TEST_CASE("a flat disk through a body is left out: the box alone, closed, exit 0") {
  // A box 2 x 1 x 1 and a disk across its middle, reaching out of it on
  // every side, as a propeller's disk crosses its nacelle.
  const test::TempDir dir("flat_disk");
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(2, 1, 1).Shape();
  const TopoDS_Shape disk =
      BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(1, 0.5, 0.5), gp_Dir(1, 0, 0)),
                              BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(
                                  gp_Circ(gp_Ax2(gp_Pnt(1, 0.5, 0.5), gp_Dir(1, 0, 0)), 1.2))).Wire())
          .Face();
  const std::string path = test::write_compound({box, disk}, dir / "disk.brep");
  const auto j = test::run_with_report(path + " -q --h-max 0.2 -o " + (dir / "d.vtu"), dir / "r.json", 0);
  const auto& prep = j["preparation"];
  REQUIRE(prep["components"].size() == 2);
  CHECK(prep["left_out"].size() == 1);
  for (const auto& c : prep["components"]) CHECK((c["role"] == "solid" || c["role"] == "disk"));
  check_one_closed_surface(j["mesh"]);
  CHECK(j["mesh"]["area"].get<double>() == Approx(10.0).epsilon(1e-9));
}

TEST_CASE("an open tube standing in a body, one face, is capped at its flat mouths and united like a shell") {
  // The box and a tube open at both ends standing through its top face. As
  // one open face it goes through the repair as an open shell of several
  // would: its mouths are flat loops, capped; the closed tube is united with
  // the box and its part inside (the lower cap with it) dropped.
  const test::TempDir dir("open_tube");
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(2, 1, 1).Shape();
  const TopoDS_Shape tube =
      BRepBuilderAPI_MakeFace(gp_Cylinder(gp_Ax3(gp_Pnt(1, 0.5, 0.5), gp_Dir(0, 0, 1)), 0.3), 0, 2 * kPi, 0, 1.5)
          .Face();
  const std::string path = test::write_compound({box, tube}, dir / "tube.brep");
  const std::string args = path + " -q --h-max 0.2 -o " + (dir / "s.vtu");
  const auto j = test::run_with_report(args, dir / "r.json", 0);
  const auto& prep = j["preparation"];
  REQUIRE(prep["components"].size() == 2);
  CHECK(prep["caps_added"].get<int>() == 2);
  for (const auto& c : prep["components"]) CHECK(c["role"] == "solid");
  CHECK(prep["not_united"].empty());
  CHECK(j["mesh"]["boundary_edges"].get<int>() == 0);
  CHECK(j["mesh"]["nonmanifold_edges"].get<int>() == 0);
  CHECK(j["mesh"]["self_intersecting_pairs"].get<int>() == 0);
  CHECK(j["mesh"]["failed_faces"].empty());
  // The box's area less the tube's foot, the tube above the box (1 high)
  // and its upper cap.
  const double r = 0.3, area = 2 * (2 + 2 + 1) - kPi * r * r + 2 * kPi * r * 1.0 + kPi * r * r;
  CHECK(j["mesh"]["area"].get<double>() == Approx(area).epsilon(0.01));
}
