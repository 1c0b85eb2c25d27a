// Each component's route: the B-rep union within its budget, stopped or ended in a child, else the union of meshes.
#include <catch2/catch.hpp>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <regex>
#include <set>
#include <string>
#include <thread>

#include "core/child_process.h"
#include "tests/cli_runner.h"
#include "tests/temp_dir.h"
#include "tests/test_models.h"
#include "tests/union_checks.h"

using namespace sizemesh;
using test::check_one_closed_surface;

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
  // afterwards (junction_slivers.h). Held to the measure of composite
  // faces: under 12 degrees away from feature corners, at most 0.05%.
  CHECK(j["mesh"]["below_12deg_elsewhere"].get<double>() <= 0.0005 * j["mesh"]["triangles"].get<double>());
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
