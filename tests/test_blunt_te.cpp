// Blunt trailing edges (topology/wing_features.h, --te-cells): the base
// between the skins' two creases is found, on OpenVSP's thick-trailing-edge
// wing (a base the preparation splits off the skin at the spline's C0
// creases) and on a wing built here, and meshed with the count of elements
// asked across it, no thin triangle there.
#include <catch2/catch.hpp>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <Geom_BSplineCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>

#include <algorithm>
#include <cmath>
#include <set>

#include "cad/occt_model.h"
#include "core/predicates.h"
#include "tests/mesher_checks.h"
#include "tests/stage_runs.h"

using namespace sizemesh;

namespace {

// A straight wing of chord 1 and span 2 (along y): a 12%-thick symmetric
// profile opened to a blunt base 1% of the chord thick at x = 1 (upper and
// lower skins each one B-spline, meeting smoothly at the leading edge).
TopoDS_Shape blunt_wing() {
  auto skin = [](double side) {
    TColgp_Array1OfPnt p(1, 21);
    for (int i = 0; i <= 20; ++i) {
      const double x = 0.5 * (1 - std::cos(kPi * i / 20));
      const double t = 0.6 * (0.2969 * std::sqrt(x) - 0.126 * x - 0.3516 * x * x + 0.2843 * x * x * x -
                              0.1015 * x * x * x * x) +
                       0.0037 * x;  // half thickness 0.005 at x = 1
      p(i + 1) = gp_Pnt(x, 0, side * t);
    }
    return GeomAPI_PointsToBSpline(p, 3, 8, GeomAbs_C2, 1e-7).Curve();
  };
  const Handle(Geom_BSplineCurve) upper = skin(1), lower = skin(-1);
  const TopoDS_Edge u = BRepBuilderAPI_MakeEdge(upper), l = BRepBuilderAPI_MakeEdge(lower);
  const TopoDS_Edge base = BRepBuilderAPI_MakeEdge(upper->EndPoint(), lower->EndPoint());
  const TopoDS_Wire wire = BRepBuilderAPI_MakeWire(u, base, l);
  const TopoDS_Face profile = BRepBuilderAPI_MakeFace(wire, true);
  return BRepPrimAPI_MakePrism(profile, gp_Vec(0, 2, 0)).Shape();
}

struct Across {
  int stations = 0, fewest_crossed = 1 << 30;
  double smallest_angle = 180, mean_edge = 0;
};

// The base's triangles (faces of the run's blunt bases): their smallest
// angle and mean edge, and at `n` stations along the span (planes y =
// const, the base running along y) the fewest triangles one station
// crosses. A strip of triangles of size w / N across a base w wide has N
// rows; a line across a row crosses two of its triangles, one where it
// passes through a node between rows: 2 N - 1 at least.
Across across_base(const RunResult& r, int n) {
  const SurfaceMesh& m = r.mesh;
  std::set<int> faces;
  for (const WingFeatures::Base& b : r.params.wing.bases) faces.insert(b.faces.begin(), b.faces.end());
  std::vector<std::array<int, 3>> tris;
  for (size_t t = 0; t < m.tris.size(); ++t)
    if (faces.count(m.tri_face[t])) tris.push_back(m.tris[t]);
  Across a;
  if (tris.empty()) return a;
  double y0 = HUGE_VAL, y1 = -HUGE_VAL;
  for (const auto& t : tris)
    for (int v : t) y0 = std::min(y0, m.xyz[v].y()), y1 = std::max(y1, m.xyz[v].y());
  for (const auto& t : tris) {
    a.smallest_angle = std::min(a.smallest_angle, min_angle_deg(m.xyz[t[0]], m.xyz[t[1]], m.xyz[t[2]]));
    for (int k = 0; k < 3; ++k) a.mean_edge += (m.xyz[t[k]] - m.xyz[t[(k + 1) % 3]]).norm() / (3.0 * tris.size());
  }
  for (int i = 1; i <= n; ++i) {
    const double y = y0 + (y1 - y0) * i / (n + 1);
    int crossed = 0;
    for (const auto& t : tris) {
      double lo = HUGE_VAL, hi = -HUGE_VAL;
      for (int v : t) lo = std::min(lo, m.xyz[v].y()), hi = std::max(hi, m.xyz[v].y());
      crossed += lo < y && hi > y;
    }
    a.fewest_crossed = std::min(a.fewest_crossed, crossed);
    ++a.stations;
  }
  return a;
}

}  // namespace

TEST_CASE("OpenVSP's thick-trailing-edge wing with --aero --te-cells 4: at least 4 elements across its base", "[models]") {
  RunOptions o = test::run_options("wing_blunt_te_openvsp.stp");
  const auto found = test::run_until(o, "topology");
  const WingFeatures& w = found->params.wing;
  // The base (split off the skin at its two creases, joined across its
  // middle seam) between the skins' creases; its thickness 0.025 to 0.05 ft.
  REQUIRE(w.bases.size() == 1);
  CHECK(w.bases[0].faces.size() == 2);
  CHECK(w.trailing.size() == 2);
  CHECK(w.leading.size() == 1);
  CHECK(w.bases[0].width_min > 0.02);
  CHECK(w.bases[0].width_max < 0.06);
  CHECK(w.chord_max == Approx(4).epsilon(0.01));
  // Its sibling, whose base thickness passes through zero at mid-span, keeps
  // the base inside the skin (a face there would pinch): no base found.
  const auto pinched = test::run_until(test::run_options("wing_blunt_te2_openvsp.stp"), "topology");
  CHECK(pinched->params.wing.bases.empty());

  // At default settings the base's width across both its faces (a
  // composite face) sets its proximity size, w / mu_d: two rows across it,
  // no thin triangle (measured across one face alone, from a crease to the
  // middle seam the mesh crosses, it set none: slivers spanned the base).
  const auto plain = test::run_until(o);
  const Across d = across_base(*plain, 40);
  CHECK(d.fewest_crossed >= 2 * 2 - 1);
  CHECK(d.smallest_angle >= 12);

  o.sizing.le_spacing = o.sizing.te_spacing = SizingParams::kAeroSpacing;
  o.sizing.te_cells = 4;
  const auto r = test::run_until(o);
  REQUIRE(r->mesh.failures.empty());
  CHECK(r->report.quality.boundary_edges == 0);
  CHECK(r->report.quality.self_intersections == 0);
  const Across a = across_base(*r, 40);
  INFO("fewest triangles crossed " << a.fewest_crossed << ", smallest angle " << a.smallest_angle);
  CHECK(a.fewest_crossed >= 2 * 4 - 1);
  CHECK(a.smallest_angle >= 12);
}

TEST_CASE("a wing built with a 1%-thick blunt base: --te-cells elements across it, none under 12 degrees") {
  RunOptions o;
  o.verbose = false;
  o.sizing.h_max = 0.1;
  const Model model = model_from_shape(blunt_wing());
  const auto plain = test::run_model(model, o, "topology");
  const WingFeatures& w = plain->params.wing;
  REQUIRE(w.bases.size() == 1);
  CHECK(w.bases[0].width_min == Approx(0.01).epsilon(0.02));
  CHECK(w.bases[0].width_max == Approx(0.01).epsilon(0.02));
  CHECK(w.trailing.size() == 2);
  CHECK(w.leading.size() == 1);
  CHECK(w.chord_max == Approx(1).epsilon(0.02));
  for (const double cells : {4.0, 6.0}) {
    o.sizing.te_cells = cells;
    const auto r = test::run_model(model, o);
    REQUIRE(r->mesh.failures.empty());
    test::require_valid_closed(*r->model, r->mesh, r->report.quality, r->model->info().diagonal());
    const Across a = across_base(*r, 40);
    INFO(cells << " cells: fewest triangles crossed " << a.fewest_crossed << ", smallest angle " << a.smallest_angle
                << ", mean edge " << a.mean_edge);
    CHECK(a.stations == 40);
    CHECK(a.fewest_crossed >= 2 * cells - 1);
    CHECK(a.smallest_angle >= 12);
    CHECK(a.mean_edge == Approx(0.01 / cells).epsilon(0.15));  // the base is 0.01 wide
  }
  // Off by default: the base gets the proximity sizes (mu_d = 2 across it).
  o.sizing.te_cells = 0;
  const auto r = test::run_model(model, o);
  CHECK(across_base(*r, 40).fewest_crossed < 2 * 4 - 1);
}
