// The advancing front ends on every input and never leaves its region: a face
// of the OpenVSP manta where it once ran away without end, a face whose
// surface stalls across a band at its boundary, the transport's fairing
// faces whose speed jumps at every knot, the step budget,
// the ear-clipping fill of a front's leftover, and the triangle estimate that
// sets the budget.
#include <catch2/catch.hpp>

#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>

#include <cmath>

#include "background/background_mesh.h"
#include "cad/occt_model.h"
#include "mesher/advancing_front.h"
#include "mesher/discretise_curves.h"
#include "mesher/face_boundary.h"
#include "mesher/fill_front.h"
#include "core/predicates.h"
#include "mesher/mesh_surface.h"
#include "sizing/refine_background.h"
#include "sizing/size_query.h"
#include "sizing/smooth.h"
#include "sizing/triangle_estimate.h"
#include "tests/stage_runs.h"
#include "tests/test_models.h"

using namespace sizemesh;

namespace {

// Signed uv area enclosed by a face's boundary loops (holes count negative).
double loops_area(const FaceMesh& fm) {
  double a = 0;
  for (const auto& loop : fm.loops)
    for (size_t i = 0; i < loop.size(); ++i) a += orient(Vec2(0, 0), fm.uv[loop[i]], fm.uv[loop[(i + 1) % loop.size()]]);
  return 0.5 * a;
}

// Sum of the triangles' uv areas; -1 if any is not counter-clockwise.
double triangles_area(const FaceMesh& fm) {
  double a = 0;
  for (const auto& t : fm.tris) {
    const double o = orient(fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]]);
    if (!(o > 0)) return -1;
    a += 0.5 * o;
  }
  return a;
}

// The command's run of a model (app/stages.h), stopped once its size query is built.
struct Sized {
  std::unique_ptr<RunResult> run;
  const Model& model;
  const BackgroundMesh& bg;
  const SizeMap& h;
  const SizeQuery& query;
  explicit Sized(const std::string& file, bool composite = true)
      : run(test::run_until(options(file, composite), "size_query")),
        model(*run->model),
        bg(run->bg),
        h(run->sizes),
        query(*run->query) {}
  static RunOptions options(const std::string& file, bool composite) {
    RunOptions o = test::run_options(file);
    o.sizing.composite = composite;
    return o;
  }
};

}  // namespace

TEST_CASE("every front strategy stays inside the face where a front once ran away (manta face 2)", "[front]") {
  // On this face's strongly stretched parametrisation a front neighbour far
  // outside the searched box was taken as apex, and a triangle left the
  // region through a front node: the front then grew without end.
  Sized s("manta2_openvsp.stp");
  const SizeQuery& query = s.query;
  const CurveMesh cm = discretise_curves(s.model, query);
  FaceSurface fs(s.model, query, 2);
  const FaceMesh boundary = face_boundary(s.model, cm, fs);
  const double domain = loops_area(boundary);
  REQUIRE(domain > 0);
  const TriangleEstimate& e = s.run->estimate;
  const long long budget = front_step_budget(e.per_face[2], boundary.num_nodes());
  bool closed = false;
  for (int strategy = 0; strategy < kStrategyCount; ++strategy) {
    FaceMesh fm = boundary;
    const FrontResult r = advancing_front(fm, fs, strategy, budget, false);
    INFO("strategy " << strategy << ": " << fm.tris.size() << " triangles, " << r.reason);
    CHECK(r.steps <= budget);
    const double covered = triangles_area(fm);
    CHECK(covered > 0);                          // every triangle counter-clockwise in uv
    CHECK(covered <= domain * (1 + 1e-9));       // none outside the face or over another
    if (r.ok) CHECK(covered == Approx(domain).epsilon(1e-9));
    closed |= r.ok;
  }
  CHECK(closed);
  // The whole model now meshes, every face closed.
  const SurfaceMesh m = mesh_surface(s.model, query);
  CHECK(m.failures.empty());
}

TEST_CASE("the front advances from a trailing edge where the surface stalls across a band (F-16 VSP 3.11 face 32)", "[front]") {
  // The horizontal tail's upper skin: v runs 0 to 121 from the trailing edge,
  // and over its first knot span (v < 1) every row of control points is one
  // point, so the surface stays on the trailing edge with dS/dv = 0 there.
  // The curve nodes' uv lie at v = 0, where the normal is undefined and no
  // front point can be placed.
  // The B-rep face's own sizes (no composite faces: the finer map the front
  // stalls under from v = 0).
  Sized s("f16_vsp311_openvsp.stp", false);
  const SizeQuery& query = s.query;
  const CurveMesh cm = discretise_curves(s.model, query);
  FaceSurface fs(s.model, query, 32);
  REQUIRE(fs.has_band());
  const FaceMesh raw = face_boundary(s.model, cm, fs);
  const FaceMesh lifted = off_bands(raw, fs);
  REQUIRE(lifted.num_nodes() == raw.num_nodes());
  int moved = 0;
  for (int i = 0; i < raw.num_nodes(); ++i) {
    if (lifted.uv[i] == raw.uv[i]) continue;
    ++moved;
    // The same point in space, now where the surface has a normal.
    CHECK((lifted.s[i].p - raw.s[i].p).norm() < 1e-7);
    CHECK(lifted.position(i) == raw.position(i));
    CHECK(raw.s[i].n.squaredNorm() == 0);
    CHECK(lifted.s[i].n.norm() == Approx(1.0));
  }
  CHECK(moved >= 10);  // every trailing-edge node, and the two corners
  // Every strict front strategy: how many edges it leaves open at the
  // trailing edge (x = 15). From the band's edge the front advances. From
  // v = 0 it could not while the uv stretch left the band a width of its
  // own (the face was closed by the lenient fallback with a fan of slivers
  // there); the stretch now gives the band none, and v = 0 is its edge too.
  const TriangleEstimate& e = s.run->estimate;
  const long long budget = front_step_budget(e.per_face[32], raw.num_nodes());
  auto open_at_trailing_edge = [&](const FaceMesh& boundary) {
    int open = 0;
    for (int strategy = 0; strategy < kStrategyCount; ++strategy) {
      FaceMesh fm = boundary;
      const FrontResult r = advancing_front(fm, fs, strategy, budget, false);
      CHECK(triangles_area(fm) > 0);
      CHECK(triangles_area(fm) <= loops_area(boundary) * (1 + 1e-9));
      for (const auto& [a, b] : r.open_edges) open += fm.s[a].p.x() > 14.9 || fm.s[b].p.x() > 14.9;
    }
    return open;
  };
  CHECK(open_at_trailing_edge(raw) == 0);
  CHECK(open_at_trailing_edge(lifted) == 0);
}

TEST_CASE("the transport's belly fairing, its rounded corner written as ever shorter knot spans, closes at the first strict strategy", "[front]") {
  // Faces 30, 34, 37 and 41 run round the fairing's lower corner: along v
  // each knot span is four times shorter in space than the one before, down
  // to 7e-5 ft and back, 0.03 ft across which the normal turns 85 degrees.
  // With the uv stretch's intervals straddling those speed jumps, every
  // strict strategy stopped there in pockets of three nodes (face 41: 42
  // front edges left) and the faces went to the lenient run; stretched span
  // by span, the first strategy closes each of them.
  Sized s("transport_wbnp_openvsp.stp");
  const CurveMesh cm = discretise_curves(s.model, s.query);
  const TriangleEstimate& e = s.run->estimate;
  for (int face : {30, 34, 37, 41}) {
    INFO("face " << face);
    FaceSurface fs(s.model, s.query, face);
    FaceMesh boundary = off_bands(face_boundary(s.model, cm, fs), fs);
    steady_boundary_normals(boundary, fs);
    FaceMesh fm = boundary;
    const FrontResult r = advancing_front(fm, fs, 0, front_step_budget(e.per_face[face], boundary.num_nodes()), false);
    CHECK(r.ok);
    CHECK(r.open_edges.empty());
    CHECK(fm.tris.size() > 100);
    CHECK(triangles_area(fm) == Approx(loops_area(boundary)).epsilon(1e-9));
  }
}

TEST_CASE("a spent step budget stops the front with a reason, never more triangles than steps", "[front]") {
  const Model model = model_from_shape(BRepPrimAPI_MakeSphere(1.0).Shape());
  const UniformSize h(0.05);
  const CurveMesh cm = discretise_curves(model, h);
  FaceSurface fs(model, h, 1);
  FaceMesh fm = face_boundary(model, cm, fs);
  const FrontResult r = advancing_front(fm, fs, 0, 100, false);
  CHECK_FALSE(r.ok);
  CHECK(r.steps == 101);  // the step that finds the budget spent is not taken
  CHECK(fm.tris.size() <= 100);
  CHECK(r.reason.find("work budget") != std::string::npos);
  CHECK_FALSE(r.open_edges.empty());
  // With its budget the same face closes.
  FaceMesh full = face_boundary(model, cm, fs);
  CHECK(advancing_front(full, fs, 0, front_step_budget(4 * 3.14159 / (0.433 * 0.05 * 0.05), full.num_nodes()), false).ok);
}

TEST_CASE("ear clipping closes a front's leftover loop exactly, and refuses a hole", "[front]") {
  const Model model = model_from_shape(BRepPrimAPI_MakeBox(2.0, 1.0, 1.0).Shape());
  const UniformSize h(0.25);
  const CurveMesh cm = discretise_curves(model, h);
  FaceSurface fs(model, h, 1);
  FaceMesh fm = face_boundary(model, cm, fs);
  REQUIRE(fm.loops.size() == 1);
  std::vector<std::array<int, 2>> loop;
  const auto& l = fm.loops[0];
  for (size_t i = 0; i < l.size(); ++i) loop.push_back({l[i], l[(i + 1) % l.size()]});
  // Too many edges for the limit: nothing is added.
  CHECK_FALSE(fill_front(fm, fs, loop, EarTest::kFacing, static_cast<int>(loop.size()) - 1));
  CHECK(fm.tris.empty());
  REQUIRE(fill_front(fm, fs, loop, EarTest::kFacing, static_cast<int>(loop.size())));
  CHECK(fm.tris.size() == loop.size() - 2);
  CHECK(triangles_area(fm) == Approx(loops_area(fm)).epsilon(1e-12));
  // The same loop reversed bounds a hole, not a region: refused.
  FaceMesh other = face_boundary(model, cm, fs);
  std::vector<std::array<int, 2>> reversed;
  for (const auto& e : loop) reversed.push_back({e[1], e[0]});
  CHECK_FALSE(fill_front(other, fs, reversed, EarTest::kAny, 1000));
  CHECK(other.tris.empty());
}

TEST_CASE("the integral of 1/h^2 with h linear on a triangle is exact", "[estimate]") {
  // Equal corners: A / h^2.
  CHECK(inverse_square_integral(3.0, 0.5, 0.5, 0.5) == Approx(12.0));
  // Against a fine midpoint sum on the triangle (0,0), (1,0), (0,1) with h = 0.01 + x + 4 y.
  const double h1 = 0.01, h2 = 1.01, h3 = 4.01;
  const int n = 2000;
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n - i; ++j) {
      // the two sub-triangles of cell (i, j), by their centroids
      for (int up = 0; up < (j < n - i - 1 ? 2 : 1); ++up) {
        const double x = (i + (up ? 2.0 : 1.0) / 3) / n, y = (j + (up ? 2.0 : 1.0) / 3) / n;
        const double hv = h1 + (h2 - h1) * x + (h3 - h1) * y;
        sum += 0.5 / (double(n) * n) / (hv * hv);
      }
    }
  CHECK(inverse_square_integral(0.5, h1, h2, h3) == Approx(sum).epsilon(2e-3));
  // Nearly equal corners give the equal-corner value continuously.
  CHECK(inverse_square_integral(1.0, 1.0, 1.0 + 1e-7, 1.0 + 2e-7) == Approx(1.0).epsilon(1e-6));
}

TEST_CASE("the triangle estimate is within 30% of the triangles the mesher makes, per model", "[estimate]") {
  for (const char* file : {"onera_m6_wing.stp", "hemisphere_cylinder_domain.stp", "cone70_capsule_sting.step"}) {
    SECTION(file) {
      const auto run = test::run_until(test::run_options(file));
      const TriangleEstimate& e = run->estimate;
      const SurfaceMesh& m = run->mesh;
      REQUIRE(m.failures.empty());
      const double ratio = m.tris.size() / e.total;
      INFO(file << ": estimate " << e.total << ", actual " << m.tris.size());
      CHECK(ratio >= 0.7);
      CHECK(ratio <= 1.3);
      // Steps per triangle: the front rarely tries an edge twice.
      CHECK(m.stats.front_steps <= 2 * static_cast<long long>(m.tris.size()));
    }
  }
}
