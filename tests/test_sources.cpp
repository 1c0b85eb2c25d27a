// Size sources (sizing/sources.h): their regions and growth, their command-line
// and config forms, and their effect on a real wing: the mesh inside a source
// at its size, the map still graded by Eq. 11/12, the nodes it sized labelled.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "sizing/params.h"
#include "sizing/smooth.h"
#include "sizing/sources.h"
#include "tests/cli_runner.h"
#include "tests/mesher_checks.h"
#include "tests/stage_runs.h"
#include "tests/test_models.h"

using namespace sizemesh;

TEST_CASE("size sources: the distance to each region and the size grown from it") {
  SizeSource box = parse_source("box 0 0 0 2 3 4 0.5");
  CHECK(box.distance(Vec3(1, 1, 1)) == 0);
  CHECK(box.distance(Vec3(5, 7, 2)) == Approx(5));  // 3 and 4 beyond a vertical edge
  CHECK(box.distance(Vec3(1, 1, -2)) == Approx(2));
  SizeSource sphere = parse_source("sphere 1 1 1 2 0.25");
  CHECK(sphere.distance(Vec3(1, 1, 2.5)) == 0);
  CHECK(sphere.distance(Vec3(1, 1, 6)) == Approx(3));
  SizeSource line = parse_source("line 0 0 0 10 0 0 1 0.1");
  CHECK(line.distance(Vec3(5, 0.5, 0)) == 0);
  CHECK(line.distance(Vec3(5, 0, 3)) == Approx(2));
  CHECK(line.distance(Vec3(13, 4, 0)) == Approx(4));  // past the end: around it, round
  SizeSource cyl = parse_source("cylinder 0 0 0 10 0 0 1 0.1");
  CHECK(cyl.distance(Vec3(10.5, 0.5, 0)) == Approx(0.5));  // past the flat end plane
  CHECK(cyl.distance(Vec3(13, 5, 0)) == Approx(5));        // 3 along, 4 out from the rim
  CHECK(cyl.distance(Vec3(5, 0, 0.9)) == 0);
  // Growth: at ln(beta) per unit length by default, to h_max over `grow` when given.
  CHECK(box.size_at(Vec3(1, 1, 1), 10, std::log(1.2)) == 0.5);
  CHECK(box.size_at(Vec3(1, 1, -2), 10, std::log(1.2)) == Approx(0.5 + 2 * std::log(1.2)));
  SizeSource grown = parse_source("box 0 0 0 2 3 4 0.5 4");
  CHECK(grown.grow == 4);
  CHECK(grown.size_at(Vec3(1, 1, -2), 10, std::log(1.2)) == Approx(0.5 + 9.5 * 0.5));
  CHECK(std::isinf(grown.size_at(Vec3(1, 1, -5), 10, std::log(1.2))));
  CHECK(source_size({box, sphere}, Vec3(1, 1, 1), 10, 0.2) == 0.25);
}

TEST_CASE("a malformed source gives one clear line: exit 2 on the command line, 1 from the config") {
  for (const char* bad : {"box 0 0 0 1 1", "cone 0 0 0 1 1", "box 1 0 0 0 1 1 0.1", "sphere 0 0 0 1 -1",
                          "sphere 0 0 0 -1 1", "cylinder 1 1 1 1 1 1 1 0.1", "line 0 0 0 1 1 x 1 0.1",
                          "sphere 0 0 nan 1 1", "point 0 0 0 1 1 -3"})
    CHECK_THROWS_AS(parse_source(bad), Error);
  const std::string wing = test::model_path("onera_m6_wing.stp");
  const auto r = test::run_sizemesh(wing + " -q --source 'box 0 0 0 1 1'");
  CHECK(r.status == 2);
  CHECK(r.err_lines() == 1);
  CHECK(r.err.find("takes 7 or 8 numbers, got 5") != std::string::npos);

  const std::string dir =
      std::filesystem::temp_directory_path().string() + "/sizemesh_src_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  auto expect_error = [&](const std::string& text, const std::string& words) {
    std::ofstream(dir + "/c.json") << text;
    const auto e = test::run_sizemesh(wing + " -q --config " + dir + "/c.json");
    INFO(text << " -> " << e.err);
    CHECK(e.status == 1);
    CHECK(e.err_lines() == 1);
    CHECK(e.err.find(words) != std::string::npos);
  };
  expect_error(R"({"sources": {"type": "box"}})", "'sources' must be a list");
  expect_error(R"({"sources": [{"type": "cone", "size": 1}]})", "has type 'cone'");
  expect_error(R"({"sources": [{"type": "box", "min": [0, 0, 0], "size": 1}]})", "needs \"max\"");
  expect_error(R"({"sources": [{"type": "sphere", "center": [0, 0], "radius": 1, "size": 1}]})",
               "center must be a list of three numbers");
  expect_error(R"({"sources": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "size": 0}]})",
               "size must be positive");
  expect_error(R"({"sources": [{"type": "line", "from": [0, 0, 0], "to": [1, 0, 0], "radius": 1, "size": 1, "r": 2}]})",
               "unknown key 'r'");
  // A good file: every kind read, with the command line's sources kept beside them.
  std::ofstream(dir + "/ok.json") << R"({"sources": [
      {"type": "box", "min": [700, 1000, -50], "max": [1200, 1250, 50], "size": 3},
      {"type": "sphere", "center": [1, 2, 3], "radius": 10, "size": 1, "grow": 200},
      {"type": "point", "center": [1, 2, 3], "radius": 0, "size": 1},
      {"type": "line", "from": [0, 0, 0], "to": [100, 0, 0], "radius": 5, "size": 2},
      {"type": "cylinder", "from": [0, 0, 0], "to": [100, 0, 0], "radius": 5, "size": 2}]})";
  SizingParams p;
  p.sources.push_back(parse_source("point 0 0 0 1 1"));
  read_config(dir + "/ok.json", p);
  REQUIRE(p.sources.size() == 6);
  CHECK(p.sources[1].kind == SizeSource::Kind::Box);
  CHECK(p.sources[1].b == Vec3(1200, 1250, 50));
  CHECK(p.sources[2].grow == 200);
  CHECK(p.sources[5].kind == SizeSource::Kind::Cylinder);
  CHECK(p.sources[5].radius == 5);
  std::filesystem::remove_all(dir);
}

TEST_CASE("a box source on the ONERA M6's tip: the mesh inside at its size, the map still graded, nodes labelled") {
  const double h_s = 3.0;  // mm; the default sizes there are 2 to 25
  const Vec3 lo(700, 1000, -50), hi(1200, 1250, 50);
  RunOptions o = test::run_options("onera_m6_wing.stp");
  SizeSource box;
  box.kind = SizeSource::Kind::Box;
  box.a = lo;
  box.b = hi;
  box.size = h_s;
  o.sizing.sources = {box};
  const auto r = test::run_until(o);
  const double diag = r->model->info().diagonal();
  test::require_valid_closed(*r->model, r->mesh, r->report.quality, diag);
  // Eq. 11/12 everywhere, the source's sizes included.
  const GradationCheck c = check_gradation(r->bg, r->sizes);
  CHECK(c.max_edge_ratio <= 1 + 1e-9);
  CHECK(c.max_triangle_ratio <= 1 + 1e-9);
  int by_source = 0;
  for (int v = 0; v < r->bg.num_vertices(); ++v) {
    by_source += r->sizes.limit[v] == Limit::Source;
    if (r->sizes.limit[v] == Limit::Source) CHECK(r->sizes.h_initial[v] <= r->sizes.h_source[v] * (1 + 1e-12));
    const bool inside = (r->bg.xyz[v].array() >= lo.array()).all() && (r->bg.xyz[v].array() <= hi.array()).all();
    if (inside) CHECK(r->sizes.h[v] <= h_s * (1 + 1e-12));
  }
  CHECK(by_source > 0);
  // The mean edge of the triangles wholly inside the box: within 15% of h_s
  // (the leading edge's curvature sizes inside pull it below).
  double sum = 0;
  int edges = 0, inside_nodes = 0, labelled = 0;
  auto in_box = [&](int n) {
    const Vec3& x = r->mesh.xyz[n];
    return (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all();
  };
  for (const auto& t : r->mesh.tris) {
    if (!in_box(t[0]) || !in_box(t[1]) || !in_box(t[2])) continue;
    for (int k = 0; k < 3; ++k) sum += (r->mesh.xyz[t[k]] - r->mesh.xyz[t[(k + 1) % 3]]).norm();
    edges += 3;
  }
  REQUIRE(edges > 3000);
  CHECK(sum / edges == Approx(h_s).epsilon(0.15));
  // Point data limited_by on the mesh: most nodes in the box sized by the source.
  REQUIRE(r->limited_by.size() == r->mesh.xyz.size());
  for (size_t n = 0; n < r->mesh.xyz.size(); ++n) {
    CHECK(r->limited_by[n] >= 0);
    CHECK(r->limited_by[n] < kNumLimits);
    if (!in_box(static_cast<int>(n))) continue;
    ++inside_nodes;
    labelled += r->limited_by[n] == static_cast<int>(Limit::Source);
  }
  CHECK(labelled > 0.5 * inside_nodes);
}

TEST_CASE("a source smaller than the background triangle it lies in is still carried by the map") {
  // A 4 mm ball on the M6's upper surface at mid-span, where the background
  // spans hundreds of millimetres: refinement samples each triangle's point
  // closest to the source.
  const Vec3 centre(488.37, 606.38, 28.31);
  RunOptions o = test::run_options("onera_m6_wing.stp");
  o.sizing.sources = {parse_source("sphere 488.37 606.38 28.31 4 1.5")};
  const auto r = test::run_until(o);
  REQUIRE(r->mesh.failures.empty());
  double sum = 0;
  int edges = 0;
  for (const auto& t : r->mesh.tris) {
    bool inside = true;
    for (int n : t) inside = inside && (r->mesh.xyz[n] - centre).norm() <= 4;
    if (!inside) continue;
    for (int k = 0; k < 3; ++k) sum += (r->mesh.xyz[t[k]] - r->mesh.xyz[t[(k + 1) % 3]]).norm();
    edges += 3;
  }
  REQUIRE(edges >= 30);
  CHECK(sum / edges == Approx(1.5).epsilon(0.2));
}
