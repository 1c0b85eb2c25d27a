// The preparation on aircraft exports: IGES files laid out past column 64,
// a union that names what it could not unite instead of meshing overlapping
// components silently, and a run that ends when OpenCASCADE does not.
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <catch2/catch.hpp>
#include <gp_Circ.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <mutex>
#include <regex>
#include <set>
#include <thread>

#include "core/child_process.h"
#include "cad/iges_layout.h"
#include "cad/model.h"
#include "tests/brep_file.h"
#include "tests/cli_runner.h"
#include "tests/temp_dir.h"
#include "tests/test_models.h"

using namespace sizemesh;

namespace {

// One IGES parameter line: 64 data columns (65 when `spill`), the pointer, P, the sequence.
std::string p_line(const std::string& data, int pointer, int seq, bool spill) {
  char tail[32];
  std::snprintf(tail, sizeof tail, spill ? "%7dP%7d" : "%8dP%7d", pointer, seq);
  return data + std::string((spill ? 65 : 64) - data.size(), ' ') + tail;
}

std::string line(const std::string& data, char section, int seq) {
  char tail[16];
  std::snprintf(tail, sizeof tail, "%c%7d", section, seq);
  return data + std::string(72 - data.size(), ' ') + tail;
}

// The report's mesh: one closed, consistently oriented surface with nothing
// crossing and every face meshed.
template <class Json>
void check_one_closed_surface(const Json& m) {
  CHECK(m["boundary_edges"] == 0);
  CHECK(m["nonmanifold_edges"] == 0);
  CHECK(m["orientation_conflicts"] == 0);
  CHECK(m["self_intersecting_pairs"] == 0);
  CHECK(m["failed_faces"].empty());
}

}  // namespace

TEST_CASE("IGES parameter data in column 65 are re-wrapped to 64 columns with pointers and counts updated") {
  // A point (type 116) whose data run to column 65 (the delimiter there), as pyGeo writes.
  const std::string spilled = std::string(53, ' ') + "116,1.5,2.5,";
  REQUIRE(spilled.size() == 65);
  std::string file = line("", 'S', 1) + "\n" + line("1H,,1H;;", 'G', 1) + "\n" +
                     line("     116       1       0       0       0       0       0       000000001", 'D', 1) + "\n" +
                     line("     116       0       0       2       0", 'D', 2) + "\n" +
                     p_line(spilled, 1, 1, true) + "\n" + p_line("3.25;", 1, 2, false) + "\n" +
                     line("S      1G      1D      2P      2", 'T', 1) + "\n";
  const auto fixed = realign_iges_parameters(file);
  REQUIRE(fixed);
  CHECK(fixed->lines_moved == 1);
  // The data read back: "116,1.5,2.5,3.25;" on one line, pointer 1, sequence 1.
  const std::string expect_p = "116,1.5,2.5,3.25;" + std::string(47, ' ') + "       1P      1";
  CHECK(fixed->text.find(expect_p + "\n") != std::string::npos);
  // The directory entry counts one parameter line; the terminate record one P line.
  CHECK(fixed->text.find("     116       0       0       1       0") != std::string::npos);
  CHECK(fixed->text.find("S      1G      1D      2P      1") != std::string::npos);
  // A file laid out as the standard asks is left alone.
  CHECK_FALSE(realign_iges_parameters(fixed->text));
}

TEST_CASE("the pyGeo IGES wing is read with one warning line and meshed as a half model") {
  const test::TempDir dir("union_iges");
  const std::string out = (dir / "c172.vtu");
  const auto r = test::run_sizemesh(test::model_path("c172_wing_pygeo.igs") + " -q -o " + out);
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err_lines() == 2);
  CHECK(r.err.find("12 IGES parameter lines have data in column 65") != std::string::npos);
  CHECK(r.err.find("a half model, open on the plane z = 0") != std::string::npos);
  const Model m = load_model(test::model_path("c172_wing_pygeo.igs"));
  CHECK(m.num_faces() == 6);
  CHECK(m.info().entities_failed == 0);
  // A half wing: its root airfoil (two curves, on z = 0) is all that stays open.
  CHECK(m.info().free_curves_after_sewing == 2);
  CHECK(m.info().preparation.half_model_axis == 2);
  CHECK(m.info().preparation.caps_added == 0);
}

TEST_CASE("a wing whose tips are slits and that carries its planform plane closes into one solid") {
  // OpenVSP's blunt-trailing-edge half wing: one skin face pinched to a line
  // at root and tip (two coincident edges each, which sewing cannot join),
  // and a planform plane inside, sewn to one side of the tip slit. The skin
  // is split between its slit edges, the halves sew, the plane is taken out.
  // Each half's root and tip caps collapse onto the chord, and over an area
  // where the blunt trailing edge meets them: they are split off the skin,
  // put on their planes, and the two halves of each cap merged.
  const Model m = load_model(test::model_path("wing_blunt_te_openvsp.stp"));
  const Preparation& p = m.info().preparation;
  REQUIRE(p.components.size() == 1);
  CHECK(p.components[0].role == "solid");
  CHECK(p.internal_faces_removed == 1);
  CHECK(m.closed());
  CHECK(p.faces_made_planar == 4);
  CHECK(m.num_faces() == 4);
  CHECK(m.info().solids == 1);
  CHECK(p.half_model_axis == -1);
}

TEST_CASE("components the B-rep union cannot take within its budget are united at mesh level") {
  // The F-16's union takes seconds; a budget of a tenth of one leaves every
  // attachment out of the B-rep union. They are united with the fuselage as
  // meshes: one closed surface, nothing crossing, exit 0.
  const test::TempDir dir("union_budget");
  const auto j = test::run_with_report(test::model_path("f16_openvsp.stp") + " -q --union-seconds 0.1 -o " +
                                           (dir / "f16.vtu"),
                                       (dir / "r.json"), 0);
  const auto& prep = j["preparation"];
  CHECK(prep["not_united"].empty());
  int mesh_level = 0;
  for (const auto& c : prep["components"]) {
    const std::string route = c["route"];
    mesh_level += route == "mesh-level union";
    CHECK(route.rfind("not united", 0) == std::string::npos);
  }
  CHECK(mesh_level >= 5);
  CHECK(prep["united_at_mesh_level"] == mesh_level);
  CHECK(j["mesh_union"]["united"] == mesh_level);
  CHECK(j["mesh_union"]["junction_nodes"] > 500);
  check_one_closed_surface(j["mesh"]);
  // Without a budget to run out, the same model unites whole as a B-rep.
  const auto whole =
      test::run_with_report(test::model_path("f16_openvsp.stp") + " -q --union-seconds 120", (dir / "w.json"), 0);
  CHECK(whole["preparation"]["not_united"].empty());
  // Component 7, the wing, is one body with component 2 that lies on it
  // face to face; the rest are united whole.
  const auto& whole_routes = whole["preparation"]["components"];
  for (size_t k = 0; k < whole_routes.size(); ++k)
    CHECK(whole_routes[k]["route"] ==
          (k == 6 ? "one body with component 2 (faces back to back): B-rep union" : "B-rep union"));
}

TEST_CASE("a component the mesh-union option names is united at mesh level while the others take the B-rep route") {
  const test::TempDir dir("union_mixed");
  const auto j = test::run_with_report(test::model_path("f16_openvsp.stp") + " -q --union-seconds 120 --mesh-union 5 -o " +
                                           (dir / "f16.vtu"),
                                       (dir / "r.json"), 0);
  const auto& comps = j["preparation"]["components"];
  REQUIRE(comps.size() == 7);
  for (size_t k = 0; k < comps.size(); ++k)
    CHECK(comps[k]["route"] == (k == 4   ? "mesh-level union"
                                : k == 6 ? "one body with component 2 (faces back to back): B-rep union"
                                         : "B-rep union"));
  CHECK(j["mesh_union"]["united"] == 1);
  CHECK(j["mesh"]["boundary_edges"] == 0);
  CHECK(j["mesh"]["nonmanifold_edges"] == 0);
  CHECK(j["mesh"]["self_intersecting_pairs"] == 0);
  // A word is refused; so is a component number the model does not have.
  const auto word = test::run_sizemesh(test::model_path("f16_openvsp.stp") + " -q --mesh-union wing");
  CHECK(word.status == 2);
  const auto beyond = test::run_sizemesh(test::model_path("f16_openvsp.stp") + " -q --mesh-union 8 -o " + (dir / "x.vtu"));
  CHECK(beyond.status == 1);
  CHECK(beyond.err == "sizemesh: error: --mesh-union 8: the model has 7 components (sizemesh --info lists them)\n");
}

TEST_CASE("a transport's twelve components: a B-rep union on course to miss its time is stopped early, the union of meshes takes them, every node's uv is its place on its face", "[models]") {
  // The all-at-once general fuse of the transport's components runs about
  // 40 s; its progress shows that within a quarter of its budget (16 s here,
  // so that the projection, not the budget's end, stops it on a loaded
  // machine too), so it is stopped then, and the union of meshes takes all
  // twelve.
  // Nodes the band remesh makes away from every source triangle they know
  // (the wing's upper junction on the fuselage side) take their uv from the
  // face's nearest source triangle, then the surface: no uv at a corner of
  // the parameter domain, metres from the node, which the report would count
  // as inverted triangles.
  const test::TempDir dir("union_transport_mesh");
  const auto j = test::run_with_report(
      test::model_path("transport_wbnp_openvsp.stp") + " -q --union-seconds 16 -o " + (dir / "t.vtu"), (dir / "r.json"), 0);
  const std::regex stopped(
      R"(the B-rep union of all 12 components was stopped (\d+)% through after ([\d.]+) s, on course for about (\d+) s of its ([\d.]+) s)");
  for (const auto& c : j["preparation"]["components"]) {
    const std::string why = c["brep_failure"];
    INFO(why);
    std::smatch m;
    REQUIRE(std::regex_match(why, m, stopped));
    const double after = std::stod(m[2]), about = std::stod(m[3]), budget = std::stod(m[4]);
    CHECK(after >= 0.25 * budget - 0.05);
    CHECK(after < budget);
    CHECK(about > 2.5 * budget - 0.5);
  }
  CHECK(j["preparation"]["not_united"].empty());
  CHECK(j["mesh_union"]["united"] == 12);
  check_one_closed_surface(j["mesh"]);
  CHECK(j["mesh"]["inverted_triangles"] == 0);
  // Inner nodes on their surface within 0.5% of the diagonal (26.99 ft):
  // the largest gap is a junction node left on the meshes where surfaces graze.
  CHECK(j["mesh"]["max_inner_node_distance"].get<double>() < 0.135);
  // The band remesh splits the CAD curves on its rim to the junction's size;
  // the faces beyond them (the lower fuselage under the wing root) are meshed
  // again too, or each split edge leaves a fan of 6-degree slivers there
  // (152 on that face alone, 217 avoidable in all). A curve node the cut
  // leaves a stub away from a junction corner is moved along its curve (9
  // more). The 2 left on faces the junction crosses (three junction nodes
  // around a corner, a 0.024 edge) go with the thin triangles' removal
  // afterwards (junction_slivers.h).
  CHECK(j["mesh"]["avoidable_below_12deg"] == 0);
}

TEST_CASE("a component whose skin folds through itself inside another is united at mesh level", "[models]") {
  // The manta's component 4 meshes with crossing triangles (faces 65 to 68:
  // its skin folds through itself), all inside component 6. The union drops
  // the fold with the rest of what lies inside: one closed surface, nothing
  // crossing.
  const test::TempDir dir("union_fold");
  const auto j = test::run_with_report(test::model_path("manta2_openvsp.stp") + " -q --mesh-union 4 -o " +
                                           (dir / "manta.vtu"),
                                       (dir / "r.json"), 0);
  CHECK(j["preparation"]["not_united"].empty());
  CHECK(j["preparation"]["components"][3]["route"] == "mesh-level union");
  CHECK(j["mesh_union"]["united"] == 1);
  CHECK(j["mesh_union"]["failed"] == 0);
  check_one_closed_surface(j["mesh"]);
}

TEST_CASE("the 777 nosplit meshes with no avoidable triangle under 12 degrees and none turned over", "[models]") {
  // Its fuselage's end is a vertical line written as a point (test_prepare),
  // its fin's sides hold strips collapsed onto the trailing edge where the
  // fin meets the fuselage (junction nodes found by the whole face's nearest
  // point), and its fin's root and tip sections wobble below the elements
  // (turning counted at their scale): each of those once left slivers.
  // The union's budget is pinned: on a loaded machine the default one can
  // send every component to the mesh-level union, another mesh.
  const test::TempDir dir("b777_nosplit");
  const auto j = test::run_with_report(
      test::model_path("b777_nosplit_openvsp.stp") + " -q --union-seconds 60 -o " + (dir / "b.vtu"), (dir / "r.json"), 0);
  for (const auto& c : j["preparation"]["components"])
    if (c["role"] == "solid") CHECK(c["route"].get<std::string>().find("union") != std::string::npos);
  check_one_closed_surface(j["mesh"]);
  CHECK(j["mesh"]["avoidable_below_12deg"] == 0);
  CHECK(j["mesh"]["inverted_triangles"] == 0);
}

TEST_CASE("the 777 one-piece's tail, cut by the fuselage across the seam its skins close on, has no triangle turned over", "[models]") {
  // Its tail skins run from the trailing edge round to it again on a
  // surface that is closed there without a period; the fuselage crosses
  // that seam. The cut faces' regions are walked across it as across a
  // periodic seam (Geometry::face_wrap_v), so the triangles the cut crosses
  // are remeshed instead of kept as bands of slivers, some turned over.
  const test::TempDir dir("b777_onepiece");
  const auto j = test::run_with_report(
      test::model_path("b777_onepiece_openvsp.stp") + " -q -o " + (dir / "b.vtu"), (dir / "r.json"), 0);
  check_one_closed_surface(j["mesh"]);
  CHECK(j["mesh"]["inverted_triangles"] == 0);
  // A curve's segment at a junction corner keeps its component's coarse
  // spacing unless spaced again to the junction's size (5 avoidable); of
  // the 3 left after that, the thin triangles' removal takes all (junction_slivers.h).
  CHECK(j["mesh"]["avoidable_below_12deg"] == 0);
}

TEST_CASE("a union of meshes that would lose volume is refused, and a piece wholly inside the rest is absorbed", "[models]") {
  // The F-16 from OpenVSP 3.11, every component united as meshes. The tail's
  // centre piece (component 3) is folded (its mesh crosses itself) and lies
  // inside the fuselage; CGAL's corefinement of it with the rest returned an
  // empty mesh, which crosses nowhere: kept, it took the fuselage, the wings
  // and the fin away (86% of the area lost). The union is held to bound at
  // least the volume it had; a piece it cannot add whose every node lies
  // inside the rest adds nothing and is dropped.
  const test::TempDir dir("union_volume");
  const auto j = test::run_with_report(test::model_path("f16_vsp311_openvsp.stp") + " -q --mesh-union all -o " +
                                           (dir / "f16.vtu"),
                                       (dir / "r.json"), 0);
  const auto& prep = j["preparation"];
  REQUIRE(prep["components"].size() == 8);
  double cad_area = 0;
  for (const auto& c : prep["components"]) cad_area += c["area"].get<double>();
  CHECK(j["mesh_union"]["failed"] == 0);
  check_one_closed_surface(j["mesh"]);
  // The wetted surface is two thirds of the components' area (the wings'
  // and tails' roots and the canopy's base lie inside the fuselage).
  CHECK(j["mesh"]["area"].get<double>() > 0.6 * cad_area);
  CHECK(j["mesh"]["area"].get<double>() < 0.75 * cad_area);
  // The fin's flat root face lies on the fuselage's ridged top at a 5 degree
  // angle: the fuselage pierces it along the middle, and beside that it
  // floats up to 0.0095 ft above the fuselage (h_min 0.026): a slot the mesh
  // cannot resolve, whose grazing cut and thin sides held most of the 66
  // triangles avoidably under 12 degrees. The slot is closed (the root face,
  // the side that resolves it, moves into the fuselage), and the fin's sides
  // meet the fuselage steeply: no face keeps all its triangles, none is
  // turned over. The horizontal tail's upper skin stalls across a band at
  // its trailing edge (test_front): meshed from the band's edge, it no
  // longer ends in a fan of 7 slivers there. Where the fuselage meets the
  // strakes' edges at 11 degrees, the nose's curves at 5 and the tail's
  // root beside a B-rep point, the cut faces' regions are wedges and strips
  // narrower than the elements (10 avoidably thin triangles); their short
  // edges are collapsed, their caps flipped or put on the curve beside them
  // afterwards. Where the strakes' junction runs beside the fuselage's side
  // curve (curves 2 and 7), that curve kept the fuselage's own spacing, six
  // times the junction's: its segments there are split to the junction's
  // sizes grown into the face, or 3 caps stay (a collapse turns the strakes'
  // triangles over). None of the 157,000 is avoidably under 12 degrees.
  CHECK(j["mesh_union"]["gap_nodes_closed"] > 1000);
  CHECK(j["mesh_union"]["faces_kept"] == 0);
  CHECK(j["mesh_union"]["faces_remeshed"] == 39);
  CHECK(j["mesh_union"]["thin_edges_collapsed"] > 0);
  CHECK(j["mesh"]["inverted_triangles"] == 0);
  CHECK(j["mesh"]["avoidable_below_12deg"] == 0);
  // The front leaves a few small loops turned in space on the fin's and the
  // strakes' rounded edges; closed and optimised at once, none is turned
  // or under 12 degrees, and no face needs the lenient run (10 did, after
  // every other strategy: 637,000 front steps, 4 per triangle).
  CHECK(j["mesher"]["faces_lenient"] == 0);
  CHECK(j["mesher"]["front_steps_per_triangle"].get<double>() < 2.0);
}

TEST_CASE("a general fuse that does not stop is ended at the union's budget and its components are named") {
  // Pegasus: one edge-face intersection of its untrimmed sheets runs for
  // minutes without asking whether to stop. The fuse runs in a child process
  // that is ended at the budget; the components it leaves are united as
  // meshes, each named by its route, and the run ends with one closed surface.
  const test::TempDir dir("union_child");
  const std::string args = test::model_path("pegasus_openvsp.stp") + " -q --union-seconds 1 -o " + (dir / "p.vtu");
  const auto j = test::run_with_report(args, dir / "r.json", 0);
  const auto& prep = j["preparation"];
  int at_mesh_level = 0;
  for (const auto& c : prep["components"]) at_mesh_level += c["route"] == "mesh-level union";
  // All at once ran out of its time (the repair's sewing takes the whole
  // second): no pair is tried (each would take seconds too), and all
  // sixteen bodies are united as meshes, the halves of the wing and of the
  // tail each as one.
  CHECK(at_mesh_level == 14);
  CHECK(j["mesh_union"]["united"] == at_mesh_level);
  CHECK(j["mesh_union"]["failed"] == 0);
  check_one_closed_surface(j["mesh"]);
  // The budget holds: a second of union, and the repair's sewing (10x margin).
  CHECK(j["seconds"]["prepare"].get<double>() < 30);
  // --info needs no union: it describes the 21 sewn components in seconds.
  const auto info = test::run_sizemesh(test::model_path("pegasus_openvsp.stp") + " --info", 120);
  CHECK(info.status == 0);
  CHECK(info.out.find("components:  21 after sewing") != std::string::npos);
  CHECK(info.out.find("union:       not run: --info describes the file") != std::string::npos);
}

TEST_CASE("Pegasus's propeller disks are left out of its wetted surface and its bodies united at mesh level", "[models]") {
  // Five flat open disks (one per propeller) cross the nacelles: actuator
  // disks, with fluid on both sides, no walls. They are left out, named in
  // one warning line. With every solid left apart for the union of meshes,
  // the sixteen bodies are united as meshes into one closed surface (exit 0).
  // The ventral fin's blunt trailing edge is a strip 5e-4 wide, narrower than
  // twice the sewing tolerance: sewing merged its corners, so it becomes one
  // curve; left as a face, its mesh folds and the fin cannot be united.
  const test::TempDir dir("union_disks");
  const std::string args = test::model_path("pegasus_openvsp.stp") + " -q --mesh-union all -o " + (dir / "p.vtu");
  const auto j = test::run_with_report(args, dir / "r.json", 0);
  const auto& prep = j["preparation"];
  std::vector<int> disks;
  for (size_t k = 0; k < prep["components"].size(); ++k) {
    const auto& c = prep["components"][k];
    CHECK(c["role"] != "sheet");
    if (c["role"] != "disk") continue;
    disks.push_back(static_cast<int>(k) + 1);
    CHECK(c["route"] == "left out: a flat disk a body passes through, no wall");
    CHECK(c["closed"] == false);
  }
  CHECK(disks == std::vector<int>{17, 18, 19, 20, 21});
  CHECK(prep["left_out"].get<std::vector<int>>() == disks);
  CHECK(prep["fallback"] == "");
  // Its flat root and tip caps, B-splines ruled between two curves that meet
  // at both ends, are planes before they are sewn and meshed: no triangles
  // fold over each other within a cap, and the bodies sewn from them take
  // the mesh-level union.
  CHECK(prep["faces_made_planar"].get<int>() == 72);
  CHECK(j["mesh"]["local_self_intersecting_pairs"] == 0);
  CHECK(prep["strip_faces_collapsed"] == 1);
  // The wing's and the tail's right halves are one body each with their
  // left halves (faces back to back: the test below).
  int united = 0;
  for (const auto& c : prep["components"]) united += c["route"] == "mesh-level union";
  CHECK(united == 14);
  CHECK(j["mesh_union"]["failed"] == 0);
  check_one_closed_surface(j["mesh"]);
  CHECK(j["seconds"]["prepare"].get<double>() < prep["union_seconds"].get<double>());
  const auto r = test::run_sizemesh(args);
  CHECK(r.err.find("components 17, 18, 19, 20, 21 are flat open disks a body passes through (actuator disks): "
                   "no wall, left out of the wetted surface") != std::string::npos);
}

TEST_CASE("Pegasus's wing and tail halves, each closed by its own root cap on the plane between them, are one body each", "[models]") {
  // Each half is a component of its own, closed (or nearly) by a root cap on
  // y = 0, and the two caps lie on each other, each cut in two along its own
  // line. Kept apart, the union of meshes cut the caps down to strips of no
  // area along the root: flat slivers on both sides. Joined, the repair
  // takes the four cap faces out and sews the halves at the root; the loop
  // of microns that sewing leaves where the tail's two leading edges met is
  // dropped, or the tail's mesh folds there.
  const test::TempDir dir("pegasus_halves");
  const auto j = test::run_with_report(test::model_path("pegasus_openvsp.stp") + " -q -o " + (dir / "p.vtu"),
                                       dir / "r.json", 0);
  const auto& prep = j["preparation"];
  REQUIRE(prep["components"].size() == 21);
  CHECK(prep["components"][14]["route"].get<std::string>().rfind("one body with component 2 (faces back to back): ", 0) ==
        0);
  CHECK(prep["components"][15]["route"].get<std::string>().rfind("one body with component 4 (faces back to back): ", 0) ==
        0);
  for (int k : {1, 3}) CHECK(prep["components"][k]["faces_removed"] == 4);  // both halves' two cap faces
  CHECK(prep["small_loops_dropped"] == 1);
  check_one_closed_surface(j["mesh"]);
  CHECK(j["mesh"]["inverted_triangles"] == 0);
  // 318 with the halves apart, 122 with the ventral fin's leading-edge
  // strip (0.0015 wide) filled by the front with points of its own, 5 with
  // the curves at junction corners spaced again, none with the thin
  // triangles along the junctions removed afterwards (the last: two
  // junction corners 0.004 apart, merged).
  CHECK(j["mesh"]["avoidable_below_12deg"] == 0);
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

TEST_CASE("the truss-braced wing united at mesh level is one closed surface: caps apart, back-to-back strips dropped", "[models]") {
  // OpenVSP's truss-braced wing. The wing's and the horizontal tail's root
  // caps come apart from their skins and go as back-to-back pairs, so every
  // component closes (test_prepare). Each strut's two faces both reach over
  // a flat strip at its top's trailing edge and mesh it with the same
  // triangles, facing apart (one pair each, the strip's curves counted by
  // their turning at the elements' scale): those pairs go, and no edge is
  // used four times. (The vertical tail's two faces are split at their
  // folds, and no longer both reach over its tip strip.) Every component
  // then joins the union of meshes: nothing open, nothing crossing, no face
  // left unmeshed.
  const test::TempDir dir("union_back_to_back");
  const auto j = test::run_with_report(test::model_path("tbw_sugar_openvsp.stp") + " -q --mesh-union all -o " +
                                           (dir / "t.vtu"),
                                       (dir / "r.json"), 0);
  CHECK(j["mesher"]["back_to_back_dropped"] == 4);
  CHECK(j["preparation"]["not_united"].empty());
  CHECK(j["mesh_union"]["united"] == 7);
  check_one_closed_surface(j["mesh"]);
  // Its fuselage ends in a point where the surface's u-derivative vanishes
  // too: the front placed the tip's fan from a zero metric, and triangles
  // there turned over (test_mesher, the quadratic cone).
  CHECK(j["mesh"]["inverted_triangles"] == 0);
  // The wing's leading edge lies on the fuselage's flat top within 0.001 to
  // 0.04 ft (h 0.11) over ten elements: the strip of lower skin between it
  // and the junction is merged away where it is that thin, and the junction
  // nodes that touch the curve are put on it (10 avoidable before).
  CHECK(j["mesh_union"]["thin_nodes_pinched"] > 0);
  CHECK(j["mesh"]["avoidable_below_12deg"] == 0);
  // Junction nodes no projection reaches are counted apart: the largest gap
  // is that of the nodes on their surfaces, a number.
  const auto& u = j["mesh_union"];
  CHECK(u["max_junction_gap"].is_number());
  CHECK(u["junction_nodes_unprojected"].get<int>() <= u["junction_nodes_off_surface"].get<int>());
}

TEST_CASE("the manta united at mesh level: faces meshed again on either side of a thin corner share no inner edge", "[models]") {
  // The manta's body (face 9) and a neighbour (face 17) meet along two
  // curves close together at a thin corner; each face, meshed again from its
  // cut region, joins the same two curve nodes by an inner edge (used four
  // times). The edge is flipped in one of them, as after the face mesher, or
  // both faces kept their band of cut triangles (174 avoidable slivers).
  const test::TempDir dir("manta_mesh_union");
  const auto j = test::run_with_report(test::model_path("manta2_openvsp.stp") + " -q --mesh-union all -o " +
                                           (dir / "m.vtu"),
                                       (dir / "r.json"), 0);
  CHECK(j["preparation"]["not_united"].empty());
  check_one_closed_surface(j["mesh"]);
  CHECK(j["mesh_union"]["faces_kept"] == 0);
  // 19 before the thin triangles along the junctions were collapsed, flipped or pinched.
  CHECK(j["mesh"]["avoidable_below_12deg"] <= 3);
}

TEST_CASE("a child process started after the parent used oneTBB works on every core and ends", "[union]") {
  std::atomic<int> warm{0};
  tbb::parallel_for(0, 100000, [&](int) { ++warm; });  // the parent's workers are up
  const std::string path = child_result_path();
  const ChildOutcome outcome = run_in_child(
      [](const std::string& file, bool threads) {
        std::mutex m;
        std::set<std::thread::id> ids;
        tbb::parallel_for(tbb::blocked_range<int>(0, 64, 1), [&](const tbb::blocked_range<int>&) {
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
          const std::lock_guard<std::mutex> lock(m);
          ids.insert(std::this_thread::get_id());
        });
        std::ofstream(file) << threads << " " << ids.size() << "\n";
        return true;
      },
      60.0, path);
  REQUIRE(outcome == ChildOutcome::Done);
  int threads = -1, used = 0;
  std::ifstream(path) >> threads >> used;
  std::remove(path.c_str());
  CHECK(threads == 1);
  if (tbb::info::default_concurrency() >= 2) CHECK(used >= 2);
  // The parent's own parallel work goes on after the fork.
  warm = 0;
  tbb::parallel_for(0, 1000, [&](int) { ++warm; });
  CHECK(warm == 1000);
}
