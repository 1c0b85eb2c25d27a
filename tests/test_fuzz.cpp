// Every run ends: corrupted STEP and IGES files, made deterministically from
// the test models (truncations, byte flips, deleted lines, swapped entity
// references, huge numbers, NaN text, a removed CARTESIAN_POINT), and named
// bad inputs. Each run exits 0, 1 or 3 (never a signal), within 10 s, with
// exactly one stderr line when it fails, and a written mesh is valid.
#include <catch2/catch.hpp>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <gp_Ax2.hxx>
#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sys/stat.h>
#include <unistd.h>

#include "tests/cli_runner.h"
#include "tests/temp_dir.h"
#include "tests/test_models.h"

namespace fs = std::filesystem;

namespace {

// Scratch files in one folder of this process, removed at its end.
std::string scratch(const std::string& name) {
  static const sizemesh::test::TempDir dir("fuzz");
  return dir / name;
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// Corrupted variants of one file, the same on every run.
std::vector<std::pair<std::string, std::string>> variants(const std::string& text, unsigned seed, int per_kind) {
  std::mt19937 rng(seed);
  std::vector<std::pair<std::string, std::string>> out;
  auto pick = [&](size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng); };
  for (int i = 0; i < per_kind; ++i)  // truncated at evenly spread offsets
    out.push_back({"truncated" + std::to_string(i), text.substr(0, text.size() * (i + 1) / (per_kind + 1))});
  for (int i = 0; i < per_kind; ++i) {  // a few bytes flipped
    std::string t = text;
    for (int k = 0; k < 1 + i % 4; ++k) t[pick(t.size())] ^= static_cast<char>(1 << pick(8));
    out.push_back({"flipped" + std::to_string(i), t});
  }
  std::vector<size_t> starts{0};
  for (size_t p = text.find('\n'); p != std::string::npos && p + 1 < text.size(); p = text.find('\n', p + 1))
    starts.push_back(p + 1);
  for (int i = 0; i < per_kind / 2; ++i) {  // a line deleted
    const size_t k = starts[pick(starts.size() - 1)];
    const size_t e = text.find('\n', k);
    out.push_back({"deleted_line" + std::to_string(i), text.substr(0, k) + text.substr(e + 1)});
  }
  const std::regex ref("#([0-9]+)"), number("[0-9]+\\.[0-9]*");
  for (int i = 0; i < per_kind / 2; ++i) {  // an entity reference or a number replaced
    std::string t = text;
    const size_t at = pick(t.size());
    std::smatch m;
    const std::string rest = t.substr(at);
    const char* what[] = {"#1", "#99999999", "1.E300", "NAN", "-1.E+308", "1E-320"};
    if (std::regex_search(rest, m, i % 2 ? number : ref))
      t.replace(at + m.position(0), m.length(0), what[i % 6]);
    out.push_back({"replaced" + std::to_string(i), t});
  }
  return out;
}

// A mesh file sizemesh wrote: finite coordinates, indices in range.
bool valid_vtu(const std::string& path) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* g = reader->GetOutput();
  if (!g || !g->GetPoints()) return false;
  const vtkIdType np = g->GetNumberOfPoints();
  for (vtkIdType i = 0; i < np; ++i) {
    double p[3];
    g->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) return false;
  }
  for (vtkIdType c = 0; c < g->GetNumberOfCells(); ++c) {
    vtkIdType n;
    const vtkIdType* ids;
    g->GetCellPoints(c, n, ids);
    if (n != 3) return false;
    for (vtkIdType k = 0; k < n; ++k)
      if (ids[k] < 0 || ids[k] >= np) return false;
  }
  return g->GetNumberOfCells() > 0;
}

// One run on one input: ends in time, a documented exit, one error line, a valid mesh.
void require_clean_run(const std::string& input, const std::string& options, double max_seconds = 10) {
  const std::string out = scratch("out.vtu");
  fs::remove(out);
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = sizemesh::test::run_sizemesh("-q " + options + " -o " + out + " '" + input + "'",
                                              static_cast<int>(max_seconds) + 10);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  INFO(input << ": exit " << r.status << " after " << seconds << " s; stderr: " << r.err);
  CHECK(seconds < max_seconds);
  REQUIRE((r.status == 0 || r.status == 1 || r.status == 3));
  if (r.status == 1) {
    CHECK(r.err_lines() == 1);
    CHECK(r.err.rfind("sizemesh: error: ", 0) == 0);
  } else {
    CHECK(valid_vtu(out));
  }
}

void fuzz_model(const std::string& file, const std::string& ext, const std::string& options, unsigned seed,
                int per_kind) {
  const std::string text = sizemesh::test::slurp(sizemesh::test::model_path(file));
  REQUIRE(text.size() > 1000);
  int runs = 0;
  for (const auto& [name, bytes] : variants(text, seed, per_kind)) {
    const std::string path = scratch(name + ext);
    write_file(path, bytes);
    require_clean_run(path, options);
    fs::remove(path);
    ++runs;
  }
  CHECK(runs == 3 * per_kind);
}

}  // namespace

TEST_CASE("every corrupted variant of a STEP capsule ends in time with exit 0, 1 or 3", "[fuzz]") {
  fuzz_model("cone70_capsule_sting.step", ".step", "--threads 1 --phi-c 30 --h-min 0.5", 1, 40);
}

TEST_CASE("every corrupted variant of a STEP far-field domain ends in time with exit 0, 1 or 3", "[fuzz]") {
  fuzz_model("hemisphere_cylinder_domain.stp", ".stp", "--threads 1 --phi-c 30", 2, 40);
}

TEST_CASE("every corrupted variant of an IGES plate ends in time with exit 0, 1 or 3", "[fuzz]") {
  // A small IGES written here: a plate with a round hole.
  const TopoDS_Shape plate = BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-2, -2, 0), 4, 4, 0.5).Shape(),
                                             BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), 0.8, 3).Shape())
                                 .Shape();
  IGESControl_Controller::Init();
  IGESControl_Writer writer("MM", 1);  // B-rep mode
  writer.AddShape(plate);
  writer.ComputeModel();
  const std::string iges = scratch("plate.igs");
  REQUIRE(writer.Write(iges.c_str()));
  require_clean_run(iges, "--threads 1");
  const std::string text = sizemesh::test::slurp(iges);
  int runs = 0;
  for (const auto& [name, bytes] : variants(text, 3, 24)) {
    const std::string path = scratch(name + ".igs");
    write_file(path, bytes);
    require_clean_run(path, "--threads 1");
    fs::remove(path);
    ++runs;
  }
  CHECK(runs == 72);
}

TEST_CASE("an OpenVSP aircraft with 200 bytes overwritten ends in time", "[fuzz]") {
  // The full pipeline (union of the parts that survive, sizing, meshing) on
  // broken geometry: faces whose front crowds into a corner of their uv
  // domain are stopped by the front's work budget and named as failed while
  // the rest is written. Alone on two idle cores each run takes 5-19 s
  // (seed 8: 4.5 s in the general fuse of its 13 loose sheets, which then
  // fails; seed 7: 437k triangles, 29% of them at h_min, from its damaged
  // surfaces, 11 s of meshing); the bound leaves room for a loaded machine
  // (three times slower) and the other tests running beside it. A run that
  // does not end is what this test catches.
  const std::string text = sizemesh::test::slurp(sizemesh::test::model_path("manta2_openvsp.stp"));
  REQUIRE(text.size() > 100000);
  for (unsigned seed : {7u, 8u, 9u}) {
    std::mt19937 rng(seed);
    std::string t = text;
    for (int k = 0; k < 200; ++k)
      t[std::uniform_int_distribution<size_t>(2000, t.size() - 1)(rng)] =
          static_cast<char>(std::uniform_int_distribution<int>(32, 126)(rng));
    const std::string path = scratch("manta_overwritten" + std::to_string(seed) + ".stp");
    write_file(path, t);
    require_clean_run(path, "--threads 2", 120);
    fs::remove(path);
  }
}

TEST_CASE("a STEP entity without its CARTESIAN_POINT, and cut IGES records, end with one error line or a mesh", "[fuzz]") {
  std::string text = sizemesh::test::slurp(sizemesh::test::model_path("cone70_capsule_sting.step"));
  const size_t at = text.find("CARTESIAN_POINT");
  REQUIRE(at != std::string::npos);
  const size_t line = text.rfind('\n', at) + 1, end = text.find('\n', at);
  const std::string path = scratch("no_point.step");
  write_file(path, text.substr(0, line) + text.substr(end + 1));
  require_clean_run(path, "--threads 1 --phi-c 30 --h-min 0.5");
  // The d150 IGES cut inside its parameter section: truncated.
  const std::string iges = sizemesh::test::slurp(sizemesh::test::model_path("d150_fuselage.igs"));
  const std::string cut = scratch("cut.igs");
  write_file(cut, iges.substr(0, iges.size() / 2));
  const auto r = sizemesh::test::run_sizemesh("-q -o " + scratch("x.vtu") + " " + cut, 20);
  CHECK(r.status == 1);
  CHECK(r.err.find("truncated") != std::string::npos);
}

TEST_CASE("entities the reader fails on are named by their number in the file", "[fuzz]") {
  const std::string text = sizemesh::test::slurp(sizemesh::test::model_path("cone70_capsule_sting.step"));
  // #59 is an EDGE_CURVE whose end vertex #60 is made an entity of an unknown type.
  const size_t at = text.find("\n#60 = VERTEX_POINT");
  REQUIRE(at != std::string::npos);
  const std::string bad = scratch("bad_vertex.step");
  write_file(bad, text.substr(0, at) + "\n#60 = XYZ_UNKNOWN(1);\n#6000 = " + text.substr(at + 7));
  const auto r = sizemesh::test::run_sizemesh("-q -o " + scratch("x.vtu") + " " + bad, 20);
  INFO(r.err);
  CHECK(r.status == 1);
  CHECK(r.err_lines() == 1);
  CHECK(r.err.find("entity #59 (EDGE_CURVE)") != std::string::npos);
  fs::remove(bad);
}

TEST_CASE("named bad inputs give one error line and the documented exit code", "[fuzz]") {
  const std::string model = sizemesh::test::model_path("hemisphere_cylinder_domain.stp");
  const std::string empty = scratch("empty.step"), binary = scratch("binary.stp"), fifo = scratch("pipe.step");
  write_file(empty, "");
  std::string noise(4096, '\0');
  std::mt19937 rng(7);
  for (char& c : noise) c = static_cast<char>(rng());
  write_file(binary, noise);
  fs::remove(fifo);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const std::string dir = fs::temp_directory_path().string();
  struct Case {
    std::string args;
    int status;
  };
  const std::vector<Case> cases = {
      {"-o x.vtu " + empty, 1},
      {"-o x.vtu " + binary, 1},
      {"-o x.vtu " + fifo, 1},
      {"-o x.vtu " + dir, 1},
      {"-o x.vtu /nonexistent/model.step", 1},
      {"-o /nonexistent_dir/out.vtu " + model, 1},
      {"-o x.vtu --config " + dir + " " + model, 1},
      {"-o x.vtu --background x.unknown " + model, 1},
      {"-o x.vtu --beta 0 " + model, 1},
      {"-o x.vtu --beta -1 " + model, 1},
      {"-o x.vtu --beta nan " + model, 1},
      {"-o x.vtu --beta inf " + model, 1},
      {"-o x.vtu --h-min 10 --h-max 1 " + model, 1},
      {"-o x.vtu --phi-c 0 " + model, 1},
      {"-o x.vtu --phi-c 180 " + model, 1},
      {"-o x.vtu --mu-d 0 " + model, 1},
      {"-o x.vtu --max-triangles 0 " + model, 2},
      {"-o x.vtu --max-triangles 100 " + model, 1},
      {"-o x.vtu --threads -1 " + model, 2},
      {"-o x.vtu --no-such-option " + model, 2},
  };
  for (const auto& c : cases) {
    const auto r = sizemesh::test::run_sizemesh("-q " + c.args, 20);
    INFO(c.args << " -> exit " << r.status << ", stderr: " << r.err);
    CHECK(r.status == c.status);
    CHECK(r.err_lines() == 1);
  }
  for (const auto& p : {empty, binary, fifo}) fs::remove(p);
}
