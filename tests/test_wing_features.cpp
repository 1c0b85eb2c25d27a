// Wing features (topology/wing_features.h) and the chordwise spacings at them
// (--le-spacing, --te-spacing, --aero): found on the ONERA M6 where its
// leading and trailing edges are, and the mesh there at the share of the
// local chord asked.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "app/cli_options.h"
#include "tests/cli_runner.h"
#include "tests/stage_runs.h"
#include "tests/temp_dir.h"
#include "tests/test_models.h"

using namespace sizemesh;

namespace {

// The M6's B-rep: curve 21 is the leading edge (smooth, between the lower and
// upper skins, faces 10 and 11), curve 11 the sharp trailing edge (the skins'
// flat aft strips, faces 5 and 8, meet at 165 degrees); 8 and 14 carry the
// leading edge on round the tip.
constexpr int kLeadingEdge = 21, kTrailingEdge = 11;

std::vector<Vec3> curve_points(const Geometry& g, int c, int n) {
  double t0, t1;
  g.curve_range(c, t0, t1);
  std::vector<Vec3> out;
  for (int i = 0; i <= n; ++i) out.push_back(g.eval_curve(c, t0 + (t1 - t0) * i / n));
  return out;
}

double nearest(const std::vector<Vec3>& pts, const Vec3& x) {
  double d = HUGE_VAL;
  for (const Vec3& p : pts) d = std::min(d, (p - x).norm());
  return d;
}

}  // namespace

TEST_CASE("the ONERA M6's leading and trailing edges are found, with the chord between them") {
  const auto r = test::run_until(test::run_options("onera_m6_wing.stp"), "topology");
  const WingFeatures& w = r->params.wing;
  CHECK(std::set<int>(w.trailing.begin(), w.trailing.end()) == std::set<int>{kTrailingEdge});
  CHECK(std::count(w.leading.begin(), w.leading.end(), kLeadingEdge) == 1);
  for (int c : w.leading) CHECK((c == kLeadingEdge || c == 8 || c == 14));
  // Root chord 806 mm, tip 454; measured to the nearest point of the other edge.
  CHECK(w.chord_max == Approx(806).epsilon(0.02));
  CHECK(w.chord_min > 400);
  CHECK(w.chord_min < 460);
  // Faces kept apart (--no-composite) change nothing: the faces joined across smooth curves are the same.
  RunOptions apart = test::run_options("onera_m6_wing.stp");
  apart.sizing.composite = false;
  const auto s = test::run_until(apart, "topology");
  CHECK(s->params.wing.leading == w.leading);
  CHECK(s->params.wing.trailing == w.trailing);
  // A model with no wing has none: the capsule's sharp shoulder-to-sting edges are no trailing edge.
  const auto capsule = test::run_until(test::run_options("cone70_capsule_sting.step"), "topology");
  CHECK(capsule->params.wing.empty());
}

TEST_CASE("the ONERA M6 with --aero: chordwise edges at the leading edge within 20% of 0.1% of the local chord") {
  RunOptions o = test::run_options("onera_m6_wing.stp");
  o.sizing.le_spacing = o.sizing.te_spacing = SizingParams::kAeroSpacing;
  const auto r = test::run_until(o);
  const SurfaceMesh& m = r->mesh;
  REQUIRE(m.failures.empty());
  CHECK(r->report.quality.boundary_edges == 0);
  CHECK(r->report.quality.self_intersections == 0);
  CHECK(r->report.quality.below_12 - r->report.quality.feature_corner_below_12 <= 5e-4 * m.tris.size());
  const std::vector<Vec3> te = curve_points(*r->model, kTrailingEdge, 4000);
  auto on_le = [&](int n) { return m.node_dim[n] == 1 && m.node_entity[n] == kLeadingEdge; };
  // Edges from a leading-edge node off the curve (chordwise), near five spanwise stations.
  for (double y : {100.0, 300.0, 600.0, 900.0, 1100.0}) {
    double sum = 0, wanted = 0;
    int n = 0;
    std::set<std::pair<int, int>> seen;
    for (const auto& t : m.tris)
      for (int k = 0; k < 3; ++k) {
        const int a = t[k], b = t[(k + 1) % 3];
        if (on_le(a) == on_le(b)) continue;
        const int le = on_le(a) ? a : b;
        if (std::abs(m.xyz[le].y() - y) > 15 || !seen.insert({std::min(a, b), std::max(a, b)}).second) continue;
        sum += (m.xyz[a] - m.xyz[b]).norm();
        wanted += 0.001 * nearest(te, m.xyz[le]);
        ++n;
      }
    INFO("station y = " << y << ": " << n << " edges, mean " << sum / n << " against " << wanted / n);
    REQUIRE(n >= 20);
    CHECK(sum / n == Approx(wanted / n).epsilon(0.2));
  }
  // The nodes there are labelled by the spacing's rule.
  int labelled = 0, on = 0;
  for (size_t n = 0; n < m.xyz.size(); ++n)
    if (on_le(static_cast<int>(n))) ++on, labelled += r->limited_by[n] == static_cast<int>(Limit::Aero);
  CHECK(labelled > 0.9 * on);
}

TEST_CASE("the flag --aero sets the workshop spacings where not given; the report lists the features") {
  CLI::App app;
  RunCommandLine cl;
  add_run_options(app, cl);
  app.parse("m6.stp --aero --te-spacing 0.002", false);
  finish_run_options(app, cl);
  CHECK(cl.options.sizing.le_spacing == SizingParams::kAeroSpacing);
  CHECK(cl.options.sizing.te_spacing == 0.002);
  const test::TempDir dir("aero");
  const auto r = test::run_sizemesh(test::model_path("onera_m6_wing.stp") + " -q --aero --report " + (dir / "r.json") +
                                    " --background " + (dir / "bg.vtu"));
  REQUIRE(r.status == 0);
  const std::string bg = test::slurp(dir / "bg.vtu");
  CHECK(bg.find("Name=\"wing_feature\"") != std::string::npos);
  CHECK(bg.find("Name=\"h_aero\"") != std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(test::slurp(dir / "r.json"));
  CHECK(j.at("wing").at("trailing_edges") == nlohmann::json::array({kTrailingEdge}));
  CHECK(j.at("wing").at("leading_length").get<double>() > 1381);
  CHECK(test::run_sizemesh(test::model_path("onera_m6_wing.stp") + " -q --le-spacing 1.5").status == 2);
}

TEST_CASE("wing tips: the caps at a free wing's ends, sized by --tip-spacing; none on a symmetry plane", "[models]") {
  // OpenVSP's thick-trailing-edge half wing, meshed alone: a flat cap at
  // each end (root chord 4 ft, tip chord 1), each closed by the skins and
  // the blunt base.
  RunOptions o = test::run_options("wing_blunt_te_openvsp.stp");
  o.sizing.tip_spacing = 0.01;
  const auto r = test::run_until(o);
  const WingFeatures& w = r->params.wing;
  REQUIRE(w.tips.size() == 2);
  std::vector<double> chords = {w.tips[0].chord, w.tips[1].chord};
  std::sort(chords.begin(), chords.end());
  CHECK(chords[0] == Approx(1).epsilon(0.01));
  CHECK(chords[1] == Approx(4).epsilon(0.01));
  REQUIRE(r->mesh.failures.empty());
  CHECK(r->report.quality.boundary_edges == 0);
  // Each cap meshed at 1% of its chord: the mean edge of its triangles
  // within 20% of it (the caps are flat: no curvature size comes under it).
  const SurfaceMesh& m = r->mesh;
  for (const WingFeatures::Tip& tip : w.tips) {
    double sum = 0;
    int n = 0;
    for (size_t t = 0; t < m.tris.size(); ++t) {
      if (std::find(tip.faces.begin(), tip.faces.end(), m.tri_face[t]) == tip.faces.end()) continue;
      for (int k = 0; k < 3; ++k) sum += (m.xyz[m.tris[t][k]] - m.xyz[m.tris[t][(k + 1) % 3]]).norm(), ++n;
    }
    INFO("tip of chord " << tip.chord << ": " << n / 3 << " triangles, mean edge " << sum / n);
    REQUIRE(n > 0);
    CHECK(sum / n == Approx(0.01 * tip.chord).epsilon(0.2));
  }
  // The M6 cut by its symmetry plane: the root lies on the plane, no tip;
  // its own tip is rounded (the leading edge runs on round it): no cap.
  RunOptions half = test::run_options("onera_m6_wing.stp");
  half.load.domain.symmetry_axis = 1;
  const auto m6 = test::run_until(half, "topology");
  CHECK(m6->params.wing.tips.empty());
  CHECK_FALSE(m6->params.wing.leading.empty());
}
