// The flow domain for a volume mesher: --farfield and --symmetry, written as
// TetGen .smesh and Medit .mesh. TetGen (installed by cmake/setup.sh) must
// mesh the volume between body and far field and keep every face's marker;
// on a sphere inside a far field the areas and the enclosed volume match
// their analytic values, which also proves the orientation (every normal
// points into the fluid).
#include <catch2/catch.hpp>

#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepTools.hxx>
#include <gp_Pln.hxx>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_runner.h"
#include "tests/temp_dir.h"
#include "tests/test_models.h"

namespace fs = std::filesystem;
using sizemesh::test::run_sizemesh;

namespace {

struct Surface {
  std::vector<std::array<double, 3>> xyz;
  std::vector<std::array<long, 3>> tris;  // 1-based node ids
  std::vector<int> marker;
};

// Reads a Medit .mesh as sizemesh writes it (Vertices, Triangles, End).
Surface read_medit(const std::string& path) {
  std::ifstream in(path);
  Surface s;
  std::string word;
  while (in >> word) {
    if (word == "Vertices") {
      size_t n;
      in >> n;
      s.xyz.resize(n);
      int ref;
      for (auto& p : s.xyz) in >> p[0] >> p[1] >> p[2] >> ref;
    } else if (word == "Triangles") {
      size_t n;
      in >> n;
      s.tris.resize(n);
      s.marker.resize(n);
      for (size_t t = 0; t < n; ++t) in >> s.tris[t][0] >> s.tris[t][1] >> s.tris[t][2] >> s.marker[t];
    }
  }
  return s;
}

// Reads the facets of a TetGen .smesh (one triangle per line) or the faces of
// its .face output ("index a b c marker"), as sorted node triples -> marker.
std::map<std::array<long, 3>, int> read_faces(const std::string& path, bool smesh) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  std::map<std::array<long, 3>, int> out;
  if (lines.empty()) return out;
  size_t first = 1, count = 0;
  if (smesh) {
    const long nodes = std::stol(lines[0]);
    first = nodes + 2;  // node header, nodes, facet header
    count = std::stoul(lines[nodes + 1]);
  } else {
    count = std::stoul(lines[0]);
  }
  for (size_t i = first; i < first + count && i < lines.size(); ++i) {
    std::istringstream row(lines[i]);
    long lead;
    std::array<long, 3> t;
    int marker;
    row >> lead >> t[0] >> t[1] >> t[2] >> marker;
    std::sort(t.begin(), t.end());
    out[t] = marker;
  }
  return out;
}

struct Measures {
  std::map<int, double> area;  // by marker
  double signed_volume = 0;    // divergence theorem: positive when normals point out of the enclosed volume
  long boundary_edges = 0;     // edges not shared by exactly two triangles
};

Measures measure(const Surface& s) {
  Measures m;
  std::map<std::pair<long, long>, int> edges;
  for (size_t t = 0; t < s.tris.size(); ++t) {
    const auto& a = s.xyz[s.tris[t][0] - 1];
    const auto& b = s.xyz[s.tris[t][1] - 1];
    const auto& c = s.xyz[s.tris[t][2] - 1];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    m.area[s.marker[t]] += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    m.signed_volume += (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]) / 6.0;
    for (int k = 0; k < 3; ++k) {
      const long p = s.tris[t][k], q = s.tris[t][(k + 1) % 3];
      ++edges[{std::min(p, q), std::max(p, q)}];
    }
  }
  for (const auto& [e, n] : edges) m.boundary_edges += n != 2;
  return m;
}

// Runs TetGen with quality and region flags on `file.smesh` in `dir` and
// checks that its boundary faces are exactly the facets, with their markers.
void check_tetgen_keeps_markers(const sizemesh::test::TempDir& dir, const std::string& name) {
  const std::string cmd = "cd " + dir.path.string() + " && timeout 300 tetgen -pq1.2AYQ " + name + ".smesh >tetgen.log 2>&1";
  INFO(sizemesh::test::slurp(dir / "tetgen.log"));
  REQUIRE(std::system(cmd.c_str()) == 0);
  const auto facets = read_faces(dir / (name + ".smesh"), true);
  const auto faces = read_faces(dir / (name + ".1.face"), false);
  REQUIRE(facets.size() > 1000);
  CHECK(faces.size() == facets.size());
  long mismatched = 0;
  for (const auto& [tri, marker] : faces) {
    auto it = facets.find(tri);
    mismatched += it == facets.end() || it->second != marker;
  }
  CHECK(mismatched == 0);
}

std::set<int> markers_of(const std::map<std::array<long, 3>, int>& faces) {
  std::set<int> out;
  for (const auto& [t, m] : faces) out.insert(m);
  return out;
}

}  // namespace

TEST_CASE("a far-field sphere around the ONERA M6: TetGen meshes the volume and keeps every face's marker", "[domain]") {
  sizemesh::test::TempDir dir("farfield");
  const auto report = sizemesh::test::run_with_report(
      sizemesh::test::model_path("onera_m6_wing.stp") + " -q --farfield sphere -o " + (dir / "m6.smesh"),
      dir / "m6.json");
  CHECK(report["domain"]["farfield"] == "sphere");
  CHECK(report["domain"]["bodies_inside"] == 1);
  CHECK(report["domain"]["farfield_size"].get<double>() ==
        Approx(20 * report["model"]["diagonal"].get<double>()).epsilon(1e-9));
  // The M6's 11 faces keep their ids; the far field is marker 12.
  std::set<int> expected;
  for (int m = 1; m <= 12; ++m) expected.insert(m);
  CHECK(markers_of(read_faces(dir / "m6.smesh", true)) == expected);
  check_tetgen_keeps_markers(dir, "m6");
}

TEST_CASE("a half model: the M6 root on the symmetry plane becomes the hole in it", "[domain]") {
  sizemesh::test::TempDir dir("symmetry");
  const auto r = run_sizemesh(sizemesh::test::model_path("onera_m6_wing.stp") +
                              " -q --farfield box --symmetry y -o " + (dir / "half.smesh"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE(run_sizemesh(sizemesh::test::model_path("onera_m6_wing.stp") + " -q --farfield box --symmetry y -o " +
                       (dir / "half.mesh")).status == 0);
  const Surface s = read_medit(dir / "half.mesh");
  // Faces 1-11 are the wing's (9 is its root, on the plane y = 0: cut away),
  // 12 the far field, 13 the symmetry plane.
  std::set<int> markers(s.marker.begin(), s.marker.end());
  CHECK(markers.count(9) == 0);
  CHECK(markers.count(12) == 1);
  CHECK(markers.count(13) == 1);
  const double tol = 1e-6 * 1675;  // of the wing's diagonal
  long off_plane = 0, below = 0;
  for (size_t t = 0; t < s.tris.size(); ++t)
    for (long n : s.tris[t]) {
      const double y = s.xyz[n - 1][1];
      off_plane += s.marker[t] == 13 && std::abs(y) > tol;
      below += y < -tol;
    }
  CHECK(off_plane == 0);
  CHECK(below == 0);
  CHECK(measure(s).boundary_edges == 0);
  check_tetgen_keeps_markers(dir, "half");
}

TEST_CASE("OpenVSP's blunt-trailing-edge wing: its flat root cap on the symmetry plane becomes the hole in it",
          "[domain]") {
  // One B-spline skin whose root and tip caps collapse onto their chords and
  // whose blunt trailing edge collapses to a point there. The caps are put
  // on their planes and their halves merged; the root cap is then a plane
  // face on y = 0 that the cut takes out. Both of OpenVSP's exports of this
  // wing (two layouts of the trailing edge).
  for (const char* file : {"wing_blunt_te_openvsp.stp", "wing_blunt_te2_openvsp.stp"}) {
    SECTION(file) {
      sizemesh::test::TempDir dir("blunt");
      const auto j = sizemesh::test::run_with_report(sizemesh::test::model_path(file) +
                                                         " -q --farfield box --symmetry y -o " + (dir / "half.mesh"),
                                                     dir / "r.json");
      CHECK(j["preparation"]["faces_made_planar"] == 4);
      CHECK(j["domain"]["symmetry_faces"] == 1);
      const auto& m = j["mesh"];
      CHECK(m["failed_faces"].empty());
      CHECK(m["boundary_edges"] == 0);
      CHECK(m["nonmanifold_edges"] == 0);
      CHECK(m["orientation_conflicts"] == 0);
      CHECK(m["self_intersecting_pairs"] == 0);
      CHECK(m["inverted_triangles"] == 0);
      CHECK(m["avoidable_below_12deg"] == 0);
      // The caps' sizes stay local: a background that creeps on slivers of the
      // trailing edge once flooded the whole wing with h_min.
      CHECK(m["share_at_h_min"].get<double>() < 0.02);
      const Surface s = read_medit(dir / "half.mesh");
      const double tol = 1e-6 * j["model"]["diagonal"].get<double>();
      long below = 0;
      for (const auto& x : s.xyz) below += x[1] < -tol;
      CHECK(below == 0);
      CHECK(measure(s).boundary_edges == 0);
      REQUIRE(run_sizemesh(sizemesh::test::model_path(file) +
                           " -q --farfield box --symmetry y -o " + (dir / "half.smesh"))
                  .status == 0);
      check_tetgen_keeps_markers(dir, "half");
    }
  }
}

TEST_CASE("a sphere in a half far field: areas and enclosed volume match their analytic values", "[domain]") {
  sizemesh::test::TempDir dir("analytic");
  BRepTools::Write(BRepPrimAPI_MakeSphere(1.0).Shape(), (dir / "ball.brep").c_str());
  // Far field of radius 10 and the plane z = 0 through the ball's centre.
  const auto r = run_sizemesh((dir / "ball.brep") + " -q --farfield sphere --farfield-size 10 --symmetry z -o " +
                              (dir / "ball.mesh"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  const Surface s = read_medit(dir / "ball.mesh");
  const Measures m = measure(s);
  CHECK(m.boundary_edges == 0);
  // Marker 1: the ball's face; 2: the far field; 3: the symmetry plane.
  REQUIRE(m.area.size() == 3);
  CHECK(m.area.at(1) == Approx(2 * M_PI).epsilon(0.01));
  CHECK(m.area.at(2) == Approx(2 * M_PI * 100).epsilon(0.01));
  CHECK(m.area.at(3) == Approx(M_PI * (100 - 1)).epsilon(0.01));
  // Every normal points into the fluid, so the volume enclosed between ball
  // and far field comes out negative.
  CHECK(-m.signed_volume == Approx(2.0 / 3.0 * M_PI * (1000 - 1)).epsilon(0.01));
}

TEST_CASE("flow-domain options that cannot work give one clear line", "[domain]") {
  sizemesh::test::TempDir dir("domain_errors");
  const std::string m6 = sizemesh::test::model_path("onera_m6_wing.stp") + " -o " + (dir / "x.vtu");
  BRepTools::Write(BRepBuilderAPI_MakeFace(gp_Pln(), -1, 1, -1, 1).Shape(), (dir / "sheet.brep").c_str());
  const std::vector<std::pair<std::string, std::string>> cases = {
      {m6 + " --farfield sphere --farfield-size 100", "does not enclose the body"},
      {m6 + " --farfield box --farfield-size 1e9", "more than 1000 body diagonals"},
      {m6 + " --symmetry y --symmetry-at 5000", "does not touch the body"},
      {(dir / "sheet.brep") + " -o " + (dir / "x.vtu") + " --symmetry x", "needs a closed body"}};
  for (const auto& [args, message] : cases) {
    const auto r = run_sizemesh(args + " -q", 60);
    INFO(args << "\n" << r.err);
    CHECK(r.status == 1);
    CHECK(r.err_lines() == 1);
    CHECK(r.err.find(message) != std::string::npos);
  }
  for (const char* bad : {"--farfield cylinder", "--symmetry w", "--symmetry-at inf", "--farfield-h 0"}) {
    const auto r = run_sizemesh(m6 + " -q " + bad);
    INFO(bad << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(r.err_lines() == 1);
  }
}

TEST_CASE("the manta cut in half inside a far field: every face meshed, TetGen keeps the markers", "[domain]") {
  // Its symmetry plane holds the body's section, 40000 smallest elements
  // across: the front's search there once paid for every dead edge near the
  // section and ran out of its budget.
  sizemesh::test::TempDir dir("manta_half");
  const auto r = run_sizemesh(sizemesh::test::model_path("manta2_openvsp.stp") +
                                  " -q --farfield sphere --symmetry y -o " + (dir / "half.smesh"),
                              120);
  INFO(r.err);
  REQUIRE(r.status == 0);
  check_tetgen_keeps_markers(dir, "half");
}
