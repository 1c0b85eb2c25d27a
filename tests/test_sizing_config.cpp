// Local sizing controls act where set and nowhere else; bad parameters give one clear error; the example config works.
#include <BRepPrimAPI_MakeBox.hxx>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "cad/occt_model.h"
#include "tests/cli_runner.h"
#include "tests/sizing_checks.h"
#include "tests/test_models.h"

using namespace sizemesh;
using test::Sized;
using test::size_shape;

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
