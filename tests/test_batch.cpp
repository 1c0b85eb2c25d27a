// `sizemesh batch`: one row per file in summary.csv, good files meshed,
// corrupted ones failed without stopping the rest, the same rows whatever
// the number of parallel jobs.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "tests/cli_runner.h"
#include "tests/temp_dir.h"
#include "tests/test_models.h"

namespace fs = std::filesystem;
using sizemesh::test::run_sizemesh;

namespace {

// summary.csv as rows of named fields (messages in these tests hold no commas).
std::vector<std::map<std::string, std::string>> read_summary(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::map<std::string, std::string>> rows;
  std::string line;
  std::vector<std::string> header;
  auto split = [](const std::string& l) {
    std::vector<std::string> out(1);
    bool quoted = false;
    for (char c : l) {
      if (c == '"') quoted = !quoted;
      else if (c == ',' && !quoted) out.emplace_back();
      else out.back() += c;
    }
    return out;
  };
  if (std::getline(in, line)) header = split(line);
  while (std::getline(in, line)) {
    const auto f = split(line);
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header.size() && i < f.size(); ++i) row[header[i]] = f[i];
    rows.push_back(row);
  }
  return rows;
}

// A folder with three good models, a truncated STEP and a text file named .stp.
void fill_inputs(const sizemesh::test::TempDir& dir) {
  fs::create_directories(dir.path / "in");
  for (const char* m : {"onera_m6_wing.stp", "cone70_capsule_sting.step", "hemisphere_cylinder_domain.stp"})
    fs::copy_file(sizemesh::test::model_path(m), dir.path / "in" / m);
  const std::string m6 = sizemesh::test::slurp(sizemesh::test::model_path("onera_m6_wing.stp"));
  std::ofstream(dir.path / "in" / "cut.stp") << m6.substr(0, 3000);
  std::ofstream(dir.path / "in" / "x.stp") << "not a CAD file\n";
}

}  // namespace

TEST_CASE("a batch over a folder gives one row per file, and bad files fail without stopping the rest", "[batch]") {
  sizemesh::test::TempDir dir("batch");
  fill_inputs(dir);
  const auto r = run_sizemesh("batch " + (dir / "in") + " -o " + (dir / "out") + " --jobs 2 -q", 300);
  INFO(r.err);
  CHECK(r.status == 3);
  const auto rows = read_summary(dir / "out/summary.csv");
  REQUIRE(rows.size() == 5);
  std::map<std::string, std::map<std::string, std::string>> by_stem;
  for (const auto& row : rows) by_stem[fs::path(row.at("file")).stem().string()] = row;
  for (const char* stem : {"onera_m6_wing", "cone70_capsule_sting", "hemisphere_cylinder_domain"}) {
    INFO(stem);
    const auto& row = by_stem.at(stem);
    CHECK(row.at("status") == "ok");
    CHECK(row.at("exit_code") == "0");
    const auto report = nlohmann::json::parse(sizemesh::test::slurp(dir / ("out/" + std::string(stem) + ".json")));
    CHECK(row.at("triangles") == std::to_string(report["mesh"]["triangles"].get<long>()));
    CHECK(fs::file_size(dir / ("out/" + std::string(stem) + ".vtu")) > 1000);
    CHECK(std::stod(row.at("peak_mb")) > 1);
  }
  for (const char* stem : {"cut", "x"}) {
    INFO(stem);
    CHECK(by_stem.at(stem).at("status") == "error");
    CHECK(by_stem.at(stem).at("exit_code") == "1");
    CHECK(!by_stem.at(stem).at("message").empty());
  }
  CHECK(by_stem.at("cut").at("message").find("truncated") != std::string::npos);

  // One job at a time: the same rows but for times and memory.
  const auto one = run_sizemesh("batch " + (dir / "in") + " -o " + (dir / "one") + " --jobs 1 -q", 300);
  CHECK(one.status == 3);
  const auto rows1 = read_summary(dir / "one/summary.csv");
  REQUIRE(rows1.size() == rows.size());
  for (size_t i = 0; i < rows.size(); ++i)
    for (const char* key : {"file", "status", "exit_code", "triangles", "nodes", "bad_below_12deg", "message"})
      CHECK(rows1[i].at(key) == rows[i].at(key));
}

TEST_CASE("batch options: formats, options for every file, bad inputs", "[batch]") {
  sizemesh::test::TempDir dir("batch_options");
  const std::string m6 = sizemesh::test::model_path("onera_m6_wing.stp");
  const auto msh = run_sizemesh("batch " + m6 + " -o " + (dir / "msh") + " --format msh -q -- --h-min 5", 120);
  INFO(msh.err);
  CHECK(msh.status == 0);
  CHECK(fs::exists(dir / "msh/onera_m6_wing.msh"));
  const auto report = nlohmann::json::parse(sizemesh::test::slurp(dir / "msh/onera_m6_wing.json"));
  CHECK(report["sizing"]["h_min"].get<double>() == 5.0);
  // The same file twice: two outputs, not one overwritten.
  const auto twice = run_sizemesh("batch " + m6 + " " + m6 + " -o " + (dir / "twice") + " -q", 120);
  CHECK(twice.status == 0);
  CHECK(fs::exists(dir / "twice/onera_m6_wing.vtu"));
  CHECK(fs::exists(dir / "twice/onera_m6_wing_2.vtu"));
  const auto none = run_sizemesh("batch " + (dir / "nothing*.stp") + " -o " + (dir / "none"));
  CHECK(none.status == 1);
  CHECK(none.err_lines() == 1);
  CHECK(none.err.find("no CAD file matches") != std::string::npos);
  const auto bad = run_sizemesh("batch " + m6 + " -o " + (dir / "bad") + " -- --no-such-option");
  CHECK(bad.status == 2);
  CHECK(bad.err_lines() == 1);
}

TEST_CASE("a batch of mesh families: every level written, the row with the finest level and each level's count", "[batch]") {
  sizemesh::test::TempDir dir("batch_family");
  const std::string m6 = sizemesh::test::model_path("onera_m6_wing.stp");
  const auto r = run_sizemesh("batch " + m6 + " -o " + (dir / "out") + " -q -- --family 2", 120);
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(!fs::exists(dir / "out/onera_m6_wing.vtu"));
  const auto coarse = nlohmann::json::parse(sizemesh::test::slurp(dir / "out/onera_m6_wing.L1.json"));
  const auto fine = nlohmann::json::parse(sizemesh::test::slurp(dir / "out/onera_m6_wing.L2.json"));
  CHECK(fs::exists(dir / "out/onera_m6_wing.L2.vtu"));
  const auto rows = read_summary(dir / "out/summary.csv");
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].at("status") == "ok");
  CHECK(rows[0].at("triangles") == std::to_string(fine["mesh"]["triangles"].get<long long>()));
  CHECK(rows[0].at("message") == "family: L1 " + std::to_string(coarse["mesh"]["triangles"].get<long long>()) +
                                     " triangles; L2 " + rows[0].at("triangles") + " triangles");
}
