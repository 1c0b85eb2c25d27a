// The sizemesh command: help, version, info, and one clear error line for bad input.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <set>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "sizing/options.h"
#include "app/cli_options.h"
#include "tests/cli_runner.h"
#include "tests/test_models.h"

using namespace sizemesh;
namespace fs = std::filesystem;

namespace {

// A scratch directory with the bad files the command must refuse.
struct BadFiles {
  fs::path dir = fs::temp_directory_path() / ("sizemesh_bad_" + std::to_string(::getpid()));
  BadFiles() {
    fs::create_directories(dir);
    std::ofstream(dir / "empty.step").close();
    std::ofstream(dir / "not_cad.step") << "This is a plain text file, not a CAD model.\n";
    std::ofstream(dir / "not_cad.xyz") << "1 2 3\n4 5 6\n";
    std::ofstream(dir / "no_geometry.stp")
        << "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
           "FILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n#1=CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;\n"
           "END-ISO-10303-21;\n";
    const std::string wing = test::slurp(test::model_path("onera_m6_wing.stp"));
    std::ofstream(dir / "truncated.stp") << wing.substr(0, wing.size() / 2);
    const std::string fuselage = test::slurp(test::model_path("d150_fuselage.igs"));
    std::ofstream(dir / "truncated.igs") << fuselage.substr(0, 2000);
  }
  ~BadFiles() { fs::remove_all(dir); }
  std::string operator()(const std::string& name) const { return (dir / name).string(); }
};

void expect_one_error(const test::CommandResult& r, const std::string& words) {
  INFO(r.err);
  CHECK(r.status >= 1);
  CHECK(r.status <= 3);
  CHECK(r.err_lines() == 1);
  CHECK(r.err.rfind("sizemesh: error: ", 0) == 0);
  CHECK(r.err.find(words) != std::string::npos);
}

}  // namespace

TEST_CASE("bad input gives one clear error line and a non-zero exit") {
  BadFiles bad;
  const std::string wing = test::model_path("onera_m6_wing.stp");
  expect_one_error(test::run_sizemesh(bad("missing.step")), "no such file");
  expect_one_error(test::run_sizemesh(bad.dir.string()), "is a directory");
  expect_one_error(test::run_sizemesh(bad("empty.step")), "is empty");
  expect_one_error(test::run_sizemesh(bad("not_cad.step")), "does not look like a STEP file");
  expect_one_error(test::run_sizemesh(bad("not_cad.xyz")), "unknown extension");
  expect_one_error(test::run_sizemesh(bad("truncated.stp")), "is truncated: a STEP file ends with END-ISO-10303-21;");
  expect_one_error(test::run_sizemesh(bad("truncated.igs")), "is truncated: an IGES file ends with its T (terminate) record");
  expect_one_error(test::run_sizemesh(bad("no_geometry.stp")), "contains no geometry");
  expect_one_error(test::run_sizemesh(wing + " -o /nonexistent_dir/mesh.vtu"), "cannot write");
  expect_one_error(test::run_sizemesh(wing + " -o " + bad.dir.string()), "is a directory");
  expect_one_error(test::run_sizemesh(wing + " --deflection -1"), "positive");
  expect_one_error(test::run_sizemesh(wing + " --no-such-option"), "no-such-option");
  expect_one_error(test::run_sizemesh(""), "model is required");
  // A map asking for too many triangles names the option that drives them,
  // by the flag the option table gives it.
  expect_one_error(test::run_sizemesh(wing + " -o x.vtu --max-triangles 100 --h-min 0.0001 --h-max 0.001"),
                   "most come from sizes set by h_max: raise --h-max, or --max-triangles");
}

TEST_CASE("help documents every option and version prints the version") {
  const auto help = test::run_sizemesh("--help");
  CHECK(help.status == 0);
  for (const char* opt : {"--output", "--background", "--info", "--no-sew", "--sew-tolerance", "--deflection",
                          "--angle", "--version", "--quiet"})
    CHECK(help.out.find(opt) != std::string::npos);
  // The sizing options come from one table: each is in --help and in the
  // sizing table of docs/options.md with its config key.
  const std::string options_doc = test::slurp(SIZEMESH_DOCS "/options.md");
  REQUIRE(options_doc.find("| flag | config key | default | meaning |") != std::string::npos);
  for (const SizingOption& opt : sizing_options()) {
    INFO(opt.flag);
    CHECK(help.out.find(opt.flag) != std::string::npos);
    CHECK(options_doc.find("| `" + opt.flag + "` | `" + opt.key + "` |") != std::string::npos);
  }
  CHECK(help.out.find("a flag given on the command line wins over the file") != std::string::npos);
  // Every option the command line has (app/cli_options.cpp) is in docs/options.md.
  CLI::App app;
  RunCommandLine cl;
  add_run_options(app, cl);
  for (const CLI::Option* opt : app.get_options()) {
    if (opt->get_lnames().empty()) continue;
    const std::string flag = "--" + opt->get_lnames().front();
    INFO(flag);
    CHECK(options_doc.find(flag) != std::string::npos);
    CHECK(help.out.find(flag) != std::string::npos);
  }
  const auto version = test::run_sizemesh("--version");
  CHECK(version.status == 0);
  CHECK(version.out.rfind("sizemesh ", 0) == 0);
}

TEST_CASE("info reports unit, bounding box, counts and free curves") {
  const auto r = test::run_sizemesh("--info " + test::model_path("f16_openvsp.stp"));
  REQUIRE(r.status == 0);
  CHECK(r.out.find("unit:        ft") != std::string::npos);
  CHECK(r.out.find("free curves: 212 before sewing, 0 after") != std::string::npos);
  // Seven components after sewing; the three open ones close once their
  // internal planes and the caps between their halves are taken out. The
  // wing (7) and the half wing lying on it (2) are repaired as one body.
  CHECK(r.out.find("components:  7 after sewing") != std::string::npos);
  CHECK(r.out.find("10 free curves, area 343.2") != std::string::npos);
  CHECK(r.out.find("-> solid (6 faces taken out)") != std::string::npos);
  CHECK(r.out.find("-> solid, one body with component 2 (faces back to back)\n") != std::string::npos);
  // --info describes the file: the repair, not the union (tests/test_union_routes.cpp).
  CHECK(r.out.find("union:       not run: --info describes the file, a mesh run unites its components; 8 duplicate "
                   "and 5 internal faces removed; 0 split at folds or parameter jumps; 0 flat faces put on their plane; "
                   "69 faces before, 56 after") !=
        std::string::npos);
  const auto raw = test::run_sizemesh("--info --no-union " + test::model_path("f16_openvsp.stp"));
  REQUIRE(raw.status == 0);
  CHECK(raw.out.find("free curves: 212 before sewing, 24 after") != std::string::npos);
  CHECK(raw.out.find("faces:       69 (105 before sewing)") != std::string::npos);
  CHECK(r.out.find("bounding box") != std::string::npos);
  for (const char* key : {"solids:", "shells:", "faces:", "curves:", "points:"}) CHECK(r.out.find(key) != std::string::npos);
}

TEST_CASE("the background mesh is written as .vtu with classification fields") {
  const std::string out = (fs::temp_directory_path() / ("sizemesh_bg_" + std::to_string(::getpid()) + ".vtu")).string();
  const auto r = test::run_sizemesh(test::model_path("cone70_capsule_sting.step") + " -q --background " + out);
  REQUIRE(r.status == 0);
  const std::string vtu = test::slurp(out);
  CHECK(vtu.find("UnstructuredGrid") != std::string::npos);
  CHECK(vtu.find("classification_dim") != std::string::npos);
  CHECK(vtu.find("classification_id") != std::string::npos);
  CHECK(vtu.find("face_id") != std::string::npos);
  fs::remove(out);
}

TEST_CASE("a flag on the command line wins over the config file, and the file's other keys still apply") {
  const fs::path dir = fs::temp_directory_path() / ("sizemesh_cfg_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "c.json") << R"({"h_min": 2.0, "h_max": 20.0, "beta": 1.3})";
  const std::string model = test::model_path("hemisphere_cylinder_domain.stp");
  auto sizing = [&](const std::string& flags) {
    const auto r = test::run_sizemesh("-q --config " + (dir / "c.json").string() + " " + flags + " --report " +
                                      (dir / "r.json").string() + " -o " + (dir / "m.vtu").string() + " " + model);
    INFO(r.err);
    CHECK(r.status == 0);
    return nlohmann::json::parse(test::slurp((dir / "r.json").string()))["sizing"];
  };
  const auto from_file = sizing("");
  CHECK(from_file["h_min"].get<double>() == 2.0);
  CHECK(from_file["h_max"].get<double>() == 20.0);
  const auto with_flag = sizing("--h-min 3 --no-refine-background");
  CHECK(with_flag["h_min"].get<double>() == 3.0);   // the flag
  CHECK(with_flag["h_max"].get<double>() == 20.0);  // the file
  fs::remove_all(dir);
}

TEST_CASE("the test models are the CAD files in tests/data, each with its source, in the lists for tests and benches") {
  const fs::path data = fs::path(SIZEMESH_EXAMPLES_DIR) / ".." / "tests" / "data";
  std::set<std::string> listed, present;
  for (const auto& m : test::shared_models()) listed.insert(m.file);
  for (const auto& f : test::union_corpus()) listed.insert(f);
  for (const auto& e : fs::directory_iterator(data)) {
    const std::string ext = e.path().extension().string();
    if (ext == ".stp" || ext == ".step" || ext == ".igs" || ext == ".iges" || ext == ".brep")
      present.insert(e.path().filename().string());
  }
  CHECK(listed == present);
  const std::string sources = test::slurp((data / "SOURCES.md").string());
  for (const std::string& f : present) {
    INFO(f);
    CHECK(sources.find(f) != std::string::npos);
  }
}

TEST_CASE("no test reads anything from outside the repository", "[clone]") {
  // A plain clone must pass its own tests: no test, test script or build file
  // names a folder beside the clone or a machine's own paths.
  const fs::path root = fs::canonical(fs::path(SIZEMESH_EXAMPLES_DIR) / "..");
  std::vector<fs::path> files = {root / "CMakeLists.txt", root / ".ci" / "run", root / "cmake" / "setup.sh"};
  for (const char* dir : {"tests", "tests/python", "cmake"})
    for (const auto& e : fs::directory_iterator(root / dir))
      if (e.is_regular_file()) files.push_back(e.path());
  int checked = 0;
  for (const fs::path& f : files) {
    const std::string text = test::slurp(f.string());
    // Spelled in two parts, so that this file does not name them itself.
    for (const std::string& outside : {std::string("..") + "/shared", std::string("shared") + "/models",
                                       std::string("/work") + "/", std::string("/home") + "/",
                                       std::string("/root") + "/"}) {
      INFO(f.string() << " names " << outside);
      CHECK(text.find(outside) == std::string::npos);
    }
    ++checked;
  }
  CHECK(checked > 20);
  // The models the tests use come from the tree unless the override says otherwise.
  const std::string models_cmake = test::slurp((root / "cmake" / "Models.cmake").string());
  CHECK(models_cmake.find("set(SIZEMESH_MODELS_DIR \"${CMAKE_SOURCE_DIR}/tests/data\")") != std::string::npos);
}
