// Mesh families (sizing/family.h, --family): levels from one size map scaled
// uniformly, about --family-ratio times the triangles per level, each a valid
// mesh, the finer ones closer to the CAD.
#include <catch2/catch.hpp>
#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "app/pipeline.h"
#include "sizing/family.h"
#include "tests/cli_runner.h"
#include "tests/mesher_checks.h"
#include "tests/stage_runs.h"
#include "tests/temp_dir.h"
#include "tests/test_models.h"

using namespace sizemesh;
namespace fs = std::filesystem;

namespace {

// Largest distance of the triangles' centroids and edge midpoints from the
// surface at the same uv: an upper bound on the mesh's deviation from the CAD.
double deviation(const Geometry& g, const SurfaceMesh& m) {
  double worst = 0;
  for (size_t t = 0; t < m.tris.size(); ++t) {
    const auto& tr = m.tris[t];
    const auto& uv = m.tri_uv[t];
    const Vec3 c = (m.xyz[tr[0]] + m.xyz[tr[1]] + m.xyz[tr[2]]) / 3.0;
    worst = std::max(worst, test::off_surface(g, m.tri_face[t], (uv[0] + uv[1] + uv[2]) / 3.0, c));
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, test::off_surface(g, m.tri_face[t], 0.5 * (uv[k] + uv[(k + 1) % 3]),
                                                0.5 * (m.xyz[tr[k]] + m.xyz[tr[(k + 1) % 3]])));
  }
  return worst;
}

}  // namespace

TEST_CASE("family levels: sizes scale by ratio^(-1/2) per level around the middle one; level files named .Lk") {
  CHECK(family_scale(2, 3, 3.0) == 1.0);
  CHECK(family_scale(1, 3, 3.0) == Approx(std::sqrt(3.0)));
  CHECK(family_scale(3, 3, 3.0) == Approx(1 / std::sqrt(3.0)));
  CHECK(family_scale(1, 2, 4.0) == 1.0);
  CHECK(family_scale(2, 2, 4.0) == Approx(0.5));
  CHECK(level_path("out/m6.vtu", 2) == "out/m6.L2.vtu");
  CHECK(level_path("r.json", 1) == "r.L1.json");
}

TEST_CASE("the command line's --family 3 on the ONERA M6: three meshes about 3 times apart, each valid, the middle one the default") {
  const test::TempDir dir("family");
  const std::string wing = test::model_path("onera_m6_wing.stp");
  const auto r = test::run_sizemesh(wing + " -o " + (dir / "m6.msh") + " --report " + (dir / "r.json") + " --family 3");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(!fs::exists(dir / "m6.msh"));
  CHECK(r.out.find("family: L1 ") != std::string::npos);
  std::vector<double> tris;
  for (int level = 1; level <= 3; ++level) {
    INFO("level " << level);
    REQUIRE(fs::exists(dir / ("m6.L" + std::to_string(level) + ".msh")));
    const nlohmann::json j = nlohmann::json::parse(test::slurp(dir / ("r.L" + std::to_string(level) + ".json")));
    const nlohmann::json& m = j.at("mesh");
    const double n = m.at("triangles").get<double>();
    tris.push_back(n);
    CHECK(m.at("boundary_edges") == 0);
    CHECK(m.at("nonmanifold_edges") == 0);
    CHECK(m.at("inverted_triangles") == 0);
    CHECK(m.at("self_intersecting_pairs") == 0);
    CHECK(m.at("below_12deg_elsewhere").get<double>() <= 5e-4 * n);
    CHECK(m.at("low_quality_below_24deg").get<double>() <= 5e-3 * n);
    CHECK(m.at("failed_faces").empty());
  }
  CHECK(tris[1] / tris[0] == Approx(3).margin(0.5));
  CHECK(tris[2] / tris[1] == Approx(3).margin(0.5));
  // The middle level is the map as built: the default mesh, to the byte.
  const auto d = test::run_sizemesh(wing + " -q -o " + (dir / "default.msh"));
  REQUIRE(d.status == 0);
  CHECK(test::slurp(dir / "default.msh") == test::slurp(dir / "m6.L2.msh"));
}

TEST_CASE("the finest level of a family lies closer to the CAD than the coarsest") {
  const auto sized = test::run_until(test::run_options("onera_m6_wing.stp"), "estimate");
  double dev[2];
  size_t count[2];
  for (int i = 0; i < 2; ++i) {
    const int level = i == 0 ? 1 : 3;
    const auto r = family_level(*sized, level, 3, 3.0);
    test::run_on(*r, test::run_options("onera_m6_wing.stp"), "size_query");
    REQUIRE(r->mesh.failures.empty());
    dev[i] = deviation(*r->model, r->mesh);
    count[i] = r->mesh.tris.size();
    CHECK(r->sizes.h_min == Approx(sized->sizes.h_min * family_scale(level, 3, 3.0)));
  }
  INFO("deviation coarse " << dev[0] << ", fine " << dev[1]);
  CHECK(count[1] > 6 * count[0]);
  CHECK(dev[1] < dev[0]);
}
