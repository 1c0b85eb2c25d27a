// Aircraft united at mesh level are one closed surface: nothing crossing or turned over, no avoidable thin triangle.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "tests/cli_runner.h"
#include "tests/temp_dir.h"
#include "tests/test_models.h"
#include "tests/union_checks.h"

using namespace sizemesh;
using test::check_one_closed_surface;

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

TEST_CASE("the 777 nosplit meshes with at most one triangle under 12 degrees off its feature corners and none turned over", "[models]") {
  // Its fuselage's end is a vertical line written as a point (test_prepare_openvsp),
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
  // Under 12 degrees away from feature corners: one, where the fin's
  // trailing edge meets the fuselage (the composite re-mesh leaves the
  // junction's nodes where the union put them); two without composite faces.
  CHECK(j["mesh"]["below_12deg_elsewhere"].get<int>() <= 1);
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
  // Under 12 degrees away from feature corners, as composite faces count
  // them: at most 0.05% (1 of 147k).
  CHECK(j["mesh"]["below_12deg_elsewhere"].get<double>() <= 0.0005 * j["mesh"]["triangles"].get<double>());
  // The front leaves a few small loops turned in space on the fin's and the
  // strakes' rounded edges; closed and optimised at once, none is turned
  // or under 12 degrees, and no face needs the lenient run (10 did, after
  // every other strategy: 637,000 front steps, 4 per triangle).
  CHECK(j["mesher"]["faces_lenient"] == 0);
  CHECK(j["mesher"]["front_steps_per_triangle"].get<double>() < 2.0);
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
  // No step of the preparation was stopped by its time budget (a bound on
  // work, not on this machine's seconds).
  for (const auto& c : prep["components"]) {
    const std::string failure = c["brep_failure"];
    CHECK(failure.find("stopped") == std::string::npos);
    CHECK(failure.find("within") == std::string::npos);
    CHECK(c["route"].get<std::string>().find("time ran out") == std::string::npos);
  }
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
  // junction corners 0.004 apart, merged). Two with the uv stretch taken
  // span by span (its faces meshed a little differently), both where the
  // CAD is smaller than the elements: a triangle on two B-rep points of the
  // tail's tip 0.003 apart (not one curve's ends) under a size of 0.018, and
  // one in a face of 20 triangles along the centreline, every one under 24
  // degrees.
  CHECK(j["mesh"]["avoidable_below_12deg"] <= 2);
}

TEST_CASE("the truss-braced wing united at mesh level is one closed surface: caps apart, no strip meshed back to back", "[models]") {
  // OpenVSP's truss-braced wing. The wing's and the horizontal tail's root
  // caps come apart from their skins and go as back-to-back pairs, so every
  // component closes (test_prepare_openvsp). Each strut's two faces both
  // reach over a strip at its trailing edge where the surface stands still
  // across (a knot span of dS/dv = 0: the strip is the trailing edge's
  // line). The uv stretch gives that span no width, so neither face meshes
  // over it: no triangle pair back to back is left to drop, and no edge is
  // used four times. (The vertical tail's two faces are split at their
  // folds, and no longer both reach over its tip strip.) Every component
  // then joins the union of meshes: nothing open, nothing crossing, no face
  // left unmeshed.
  const test::TempDir dir("union_back_to_back");
  const auto j = test::run_with_report(test::model_path("tbw_sugar_openvsp.stp") + " -q --mesh-union all -o " +
                                           (dir / "t.vtu"),
                                       (dir / "r.json"), 0);
  CHECK(j["mesher"]["back_to_back_dropped"] == 0);
  CHECK(j["preparation"]["not_united"].empty());
  CHECK(j["mesh_union"]["united"] == 7);
  check_one_closed_surface(j["mesh"]);
  // Its fuselage ends in a point where the surface's u-derivative vanishes
  // too: the front placed the tip's fan from a zero metric, and triangles
  // there turned over (test_parametrisation, the quadratic cone).
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

TEST_CASE("the union takes the same routes, and gives the same mesh, with 1 thread, with 2, and on a loaded machine", "[models]") {
  // The 777 (one-piece B-splines): four components united as B-reps, one at
  // mesh level, a planform plane left out. Its budget is work (cad/deadline.h):
  // a budget in wall time sent components down other routes when the
  // machine was busy (91,558 triangles instead of 104,200).
  const test::TempDir dir("union_routes");
  const std::string model = test::model_path("b777_nosplit_openvsp.stp");
  auto routes = [](const nlohmann::json& j) {
    std::vector<std::string> out;
    for (const auto& c : j["preparation"]["components"]) out.push_back(c["route"]);
    return out;
  };
  const auto one = test::run_with_report(model + " -q --threads 1 -o " + (dir / "one.stl"), dir / "one.json");
  // Two threads with two more busy threads of this process beside them.
  std::atomic<bool> busy{true};
  std::vector<std::thread> load;
  for (int i = 0; i < 2; ++i)
    load.emplace_back([&busy] {
      volatile double x = 0;
      while (busy) x = x + 1;
    });
  const auto two = test::run_with_report(model + " -q --threads 2 -o " + (dir / "two.stl"), dir / "two.json");
  busy = false;
  for (auto& t : load) t.join();
  const std::vector<std::string> r1 = routes(one), r2 = routes(two);
  CHECK(r1 == r2);
  CHECK(std::count(r1.begin(), r1.end(), "B-rep union") == 4);
  CHECK(one["mesh"]["triangles"] == two["mesh"]["triangles"]);
  const std::string a = test::slurp(dir / "one.stl"), b = test::slurp(dir / "two.stl");
  CHECK(a.size() > 84);
  CHECK(a == b);
}

TEST_CASE("the union of meshes gives the same bytes run after run: each piece's corefinement renumbered by its geometry", "[models]") {
  // The 777 one-piece: five components united as meshes. CGAL's
  // corefinement returns the same vertices in an order of its own from run
  // to run; without renumbering after each piece, one binary gave 133,312
  // or 133,314 triangles (a third of the runs differing).
  const test::TempDir dir("union_bytes");
  const std::string model = test::model_path("b777_onepiece_openvsp.stp");
  std::vector<std::string> meshes;
  for (int run = 0; run < 3; ++run) {
    const std::string out = dir / ("m" + std::to_string(run) + ".stl");
    REQUIRE(test::run_sizemesh(model + " -q --threads 1 -o " + out).status == 0);
    meshes.push_back(test::slurp(out));
  }
  CHECK(meshes[0].size() > 84);
  CHECK(meshes[0] == meshes[1]);
  CHECK(meshes[0] == meshes[2]);
}
