// Background refinement: the split background keeps every classification and
// lies on the CAD, and it lets the smoothed size grow away from small features
// where the tessellation alone cannot.
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <gp_Ax2.hxx>

#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <set>

#include "cad/occt_model.h"
#include "sizing/initial_sizes.h"
#include "sizing/refine_background.h"
#include "sizing/size_query.h"
#include "sizing/smooth.h"
#include "sizing/triangle_estimate.h"
#include "tests/background_checks.h"
#include "tests/stage_runs.h"
#include "tests/test_models.h"

using namespace sizemesh;

TEST_CASE("refined backgrounds stay classified, on the CAD and watertight (test_size_smoothing checks their smoothed sizes)") {
  for (const auto& sm : test::shared_models()) {
    SECTION(sm.file) {
      Model model = load_model(test::model_path(sm.file));
      BackgroundMesh bg = build_background_mesh(model);
      const double diag = model.info().diagonal(), area_before = bg.area();
      RefineStats stats;
      SizeMap m = refine_background(model, bg, SizingParams{}, diag, &stats);
      CHECK(stats.vertices_after == bg.num_vertices());
      CHECK(stats.vertices_after - stats.vertices_before == stats.edges_split);  // one vertex per split
      CHECK(stats.rounds <= kRefineMaxRounds);
      CHECK(m.h_initial.size() == bg.xyz.size());
      // Every use's uv lands on its vertex; curve vertices sit at their parameter.
      const double tol = 2e-3 * diag;  // twice the tessellation's deflection
      for (const FacePatch& patch : bg.patches) {
        for (size_t l = 0; l < patch.vertex.size(); ++l)
          CHECK((model.eval_face(patch.face, patch.uv[l]).p - bg.xyz[patch.vertex[l]]).norm() <= tol);
        for (const auto& t : patch.tris) {  // counter-clockwise in uv, as built
          const Vec2 a = patch.uv[t[1]] - patch.uv[t[0]], b = patch.uv[t[2]] - patch.uv[t[0]];
          CHECK(a.x() * b.y() - a.y() * b.x() > 0);
        }
      }
      for (int v = 0; v < bg.num_vertices(); ++v)
        if (bg.dim[v] == 1) CHECK((model.eval_curve(bg.entity[v], bg.curve_t[v]) - bg.xyz[v]).norm() <= 1e-9 * diag);
      if (sm.closed) CHECK(test::open_background_edges(model, bg) == 0);
      CHECK(std::abs(bg.area() - area_before) <= 0.01 * area_before);
    }
  }
}

TEST_CASE("away from small holes in a large flat face the size grows at the gradation rate only with refinement") {
  // A 100 mm cube with eight holes of radius 0.5 through it around its centre
  // line: the top face is a plane whose tessellation spans the 80 mm between
  // holes with triangles whose corners all carry the holes' small sizes.
  TopoDS_Shape shape = BRepPrimAPI_MakeBox(100.0, 100.0, 100.0).Shape();
  for (const auto& [x, y] : {std::pair{10.0, 10.0}, {50.0, 10.0}, {90.0, 10.0}, {10.0, 50.0}, {90.0, 50.0},
                             {10.0, 90.0}, {50.0, 90.0}, {90.0, 90.0}})
    shape = BRepAlgoAPI_Cut(shape, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, y, -1), gp_Dir(0, 0, 1)), 0.5, 102.0).Shape())
                .Shape();
  auto size_at = [&](bool refine, const Vec3& p, double& h_hole) {
    RunOptions o;
    o.verbose = false;
    o.sizing.refine_background = refine;
    o.sizing.local_proximity = false;
    const auto run = test::run_model(model_from_shape(shape), o, "size_query");  // the command's stages
    const Model& model = *run->model;
    const BackgroundMesh& bg = run->bg;
    const SizeMap& m = run->sizes;
    h_hole = kNoLimit;
    for (int v = 0; v < bg.num_vertices(); ++v) h_hole = std::min(h_hole, m.h[v]);
    int top = 0;
    for (int f = 1; f <= model.num_faces() && !top; ++f) {
      Vec2 uv(0, 0);
      if (model.project_to_face(f, p, uv) && (model.eval_face(f, uv).p - p).norm() < 1e-9) top = f;
    }
    REQUIRE(top > 0);
    Vec2 uv(0, 0);
    REQUIRE(model.project_to_face(top, p, uv));
    const SizeQuery& q = *run->query;
    int hint = -1;
    return q.at(top, uv, hint);
  };
  const Vec3 p(50, 50, 100);  // on the top face, 39.5 from the nearest hole
  double hole_refined, hole_plain;
  const double refined = size_at(true, p, hole_refined), plain = size_at(false, p, hole_plain);
  const double graded = std::min(0.05 * std::sqrt(3.0) * 100, hole_refined + std::log(1.2) * 39.5);  // 7.2
  INFO("refined " << refined << ", plain " << plain << ", graded bound " << graded);
  CHECK(hole_refined == Approx(hole_plain));
  CHECK(refined <= graded * (1 + 1e-9));
  CHECK(refined >= 0.5 * graded);
  CHECK(plain < 0.5 * graded);  // the tessellation alone keeps the hole's size far out
}

TEST_CASE("refinement finds a curvature peak the tessellation stepped over") {
  // Face 63 of the d150 fuselage bends to a radius of about 453 mm between
  // background vertices that all see 1250 mm or more.
  Model model = load_model(test::model_path("d150_fuselage.igs"));
  const int face = 63;
  auto smallest_radius = [&](const FacePatch& patch) {
    double k_max = 0;
    for (const Vec2& uv : patch.uv) {
      double k = 0;
      if (model.max_curvature(face, uv, k)) k_max = std::max(k_max, k);
    }
    return 1 / k_max;
  };
  double k_true = 0;  // the face's own smallest radius, on a fine uv grid
  const UVBox box = model.face_uv_bounds(face);
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j <= 200; ++j) {
      const Vec2 uv = box.lo + Vec2(i / 200.0 * (box.hi - box.lo).x(), j / 200.0 * (box.hi - box.lo).y());
      double k = 0;
      if (model.max_curvature(face, uv, k)) k_true = std::max(k_true, k);
    }
  const double r_true = 1 / k_true;
  BackgroundMesh bg = build_background_mesh(model);
  const double r_tessellation = smallest_radius(bg.patches[face - 1]);
  SizingParams p;  // a deviation bound, as a user asking for an accurate surface would give
  const double diag = model.info().diagonal();
  p.h_min = diag / 1e4;
  p.deviation = 2.5e-5 * diag;
  refine_background(model, bg, p, diag);
  const double r_refined = smallest_radius(bg.patches[face - 1]);
  INFO("true " << r_true << ", tessellation " << r_tessellation << ", refined " << r_refined);
  CHECK(r_tessellation > 2 * r_true);
  CHECK(r_refined <= 1.1 * r_true);
}

TEST_CASE("refinement splits flat background triangles before the triangle stage lowers a whole model to one gap's size") {
  // The impeller at a coarse accuracy (h_min diag / 1e4, h_max diag / 20,
  // phi_c 30, deviation 3.2e-3 diag): a few fluid-gap vertices of about 1 mm
  // among sizes of 60 mm. A background triangle with a corner close to its
  // long opposite edge has a linear size gradient (Eq. 11) of the size
  // difference over that short height, so the triangle stage lowers the far
  // corners to the near one's size and the edge stage carries that over the
  // face: the map asked for 205k triangles where the edge stage alone (Eq. 12)
  // asked for 27k. Split first, such triangles let the sizes grade.
  // The command's stages, stopped once the model is prepared to set sizes
  // relative to its diagonal, then run on to the smoothing, twice.
  const RunOptions o = test::run_options("impeller_laufrad.stp");
  const auto prepared = test::run_until(o, "prepare");
  const Model& model = *prepared->model;
  const double diag = model.info().diagonal();
  for (bool refine : {true, false}) {
    const auto run = test::run_model(model, o, "background");
    SizingParams& p = run->params;
    p.h_min = diag / 1e4;
    p.h_max = diag / 20;
    p.phi_c_deg = 30;
    p.deviation = 3.2e-3 * diag;
    p.refine_background = refine;
    test::run_on(*run, o, "initial_sizes", "smoothing");
    const BackgroundMesh& bg = run->bg;
    const SizeMap& m = run->sizes;
    std::vector<double> edge_only = m.h_initial;
    smooth_edges(bg, m.edge_log_beta, edge_only);
    const double n_edge = estimate_triangles(bg, edge_only, {}, model.num_faces()).total;
    const double n_both = estimate_triangles(bg, m.h, {}, model.num_faces()).total;
    INFO((refine ? "refined" : "tessellation") << ": edge stage " << n_edge << ", both stages " << n_both);
    CHECK(n_both >= n_edge);  // the triangle stage only lowers
    if (refine) CHECK(n_both <= 1.5 * n_edge);
    else CHECK(n_both > 3 * n_edge);  // without refinement the flat triangles stay
  }
}

namespace {

// Pairs of triangles inside a face whose opposite angles sum to more than
// pi + margin (not Delaunay in space).
int non_delaunay_pairs(const BackgroundMesh& bg, double margin) {
  std::map<int, std::vector<int>> tris_of_edge;
  for (int t = 0; t < bg.num_triangles(); ++t)
    for (int e : bg.tri_edges[t])
      if (bg.edge_curve[e] == 0) tris_of_edge[e].push_back(t);
  auto opposite_angle = [&](int t, int e) {
    const auto& tr = bg.tris[t];
    for (int k = 0; k < 3; ++k) {
      const int o = tr[k];
      if (o == bg.edges[e][0] || o == bg.edges[e][1]) continue;
      const Vec3 u = bg.xyz[bg.edges[e][0]] - bg.xyz[o], v = bg.xyz[bg.edges[e][1]] - bg.xyz[o];
      return std::atan2(u.cross(v).norm(), u.dot(v));
    }
    return 0.0;
  };
  int n = 0;
  for (const auto& [e, ts] : tris_of_edge)
    if (ts.size() == 2 && bg.tri_face[ts[0]] == bg.tri_face[ts[1]])
      n += opposite_angle(ts[0], e) + opposite_angle(ts[1], e) > kPi + margin;
  return n;
}

}  // namespace

TEST_CASE("Delaunay flips keep the M6's background classified and closed, and its smoothed map asks for fewer triangles") {
  // The wing's skins are tessellated in uv, chordwise against spanwise: long
  // obtuse triangles whose short heights make Eq. 11 lower sizes far from
  // the leading and trailing edges.
  Model model = load_model(test::model_path("onera_m6_wing.stp"));
  const double diag = model.info().diagonal();
  SizingParams params;
  BackgroundMesh bg = build_background_mesh(model);
  const BackgroundMesh before = bg;
  const int unflipped = non_delaunay_pairs(bg, 0.3);
  const int flips = flip_to_delaunay(bg, model);
  INFO("flips " << flips << ", non-Delaunay pairs before " << unflipped << ", after " << non_delaunay_pairs(bg, 0.3));
  CHECK(flips > 0);
  CHECK(unflipped > 100);
  CHECK(non_delaunay_pairs(bg, 0.3) <= unflipped / 20);
  // Same vertices, same number of triangles per face, closed, counter-clockwise in uv.
  CHECK(bg.xyz == before.xyz);
  CHECK(bg.num_triangles() == before.num_triangles());
  for (size_t f = 0; f < bg.patches.size(); ++f) {
    CHECK(bg.patches[f].tris.size() == before.patches[f].tris.size());
    for (const auto& t : bg.patches[f].tris) {
      const Vec2 a = bg.patches[f].uv[t[1]] - bg.patches[f].uv[t[0]], b = bg.patches[f].uv[t[2]] - bg.patches[f].uv[t[0]];
      CHECK(a.x() * b.y() - a.y() * b.x() > 0);
    }
  }
  CHECK(test::open_background_edges(model, bg) == 0);
  CHECK(std::abs(bg.area() - before.area()) <= 0.01 * before.area());
  // Curve edges are never flipped.
  auto curve_edge_set = [](const BackgroundMesh& m) {
    std::set<std::pair<int, int>> s;
    for (size_t e = 0; e < m.edges.size(); ++e)
      if (m.edge_curve[e]) s.insert({m.edges[e][0], m.edges[e][1]});
    return s;
  };
  CHECK(curve_edge_set(bg) == curve_edge_set(before));
  // What it is for: with the refinement (which flips before and after each
  // round of splits), the smoothed map asks for fewer triangles, at default
  // settings and, far fewer, under a deviation bound of 4e-4 of the diagonal
  // (measured 0.92 and 0.74).
  // The command's stages, with the refinement's flips left out in one run
  // (its stage swapped for one without them).
  auto asked_refined = [&](const SizingParams& p0, bool flips) {
    RunOptions o;
    o.verbose = false;
    o.sizing = p0;
    Stages stages = until(from(all_stages(), "background"), "estimate");
    if (!flips)
      stages = replaced(stages, "refine_background", [](RunResult& r, const RunOptions&, const WarningSink&) {
        refine_background(*r.model, r.bg, r.params, r.model->info().diagonal(), r.sizes, &r.report.refinement, false);
      });
    std::unique_ptr<RunResult> r = start_run(o);
    r->model.emplace(model);
    run_stages(*r, o, test::quiet(), stages);
    return r->estimate.total;
  };
  SizingParams bounded;
  bounded.phi_c_deg = 90;
  bounded.deviation = 4e-4 * diag;
  bounded.h_min_rel = 1e-4;
  const double default_before = asked_refined(params, false), default_after = asked_refined(params, true);
  const double bounded_before = asked_refined(bounded, false), bounded_after = asked_refined(bounded, true);
  INFO("triangles asked for at default settings " << default_before << " -> " << default_after
                                                   << ", under the bound " << bounded_before << " -> " << bounded_after);
  CHECK(default_after < 0.95 * default_before);
  CHECK(bounded_after < 0.85 * bounded_before);
}

TEST_CASE("the curvature memo gives the sizes computed without it, and answers what it was asked before") {
  Model model = load_model(test::model_path("onera_m6_wing.stp"));
  BackgroundMesh bg = build_background_mesh(model);
  const SizingParams p{};
  refine_background(model, bg, p, model.info().diagonal());
  CurvatureMemo memo;
  const std::vector<double> fresh = curvature_sizes(model, bg, p);
  const std::vector<double> first = curvature_sizes(model, bg, p, &memo);   // fills the memo
  const std::vector<double> second = curvature_sizes(model, bg, p, &memo);  // answers from it
  REQUIRE(fresh.size() == static_cast<size_t>(bg.num_vertices()));
  CHECK(first == fresh);
  CHECK(second == fresh);
  int uses = 0, curved = 0;
  for (int v = 0; v < bg.num_vertices(); ++v)
    for (int u = bg.use_start[v]; u < bg.use_start[v + 1]; ++u, ++uses) {
      const int f = bg.use_face[u];
      const Vec2& uv = bg.patches[f - 1].uv[bg.use_local[u]];
      double h = -1;
      REQUIRE(memo.find(f, uv, h));
      CHECK(h == face_curvature_size(model, f, uv, p));
      curved += h < kNoLimit;
    }
  CHECK(uses > bg.num_vertices());  // curve vertices lie on two faces
  CHECK(curved > 0);
  // A uv never asked is not in it.
  double h = 0;
  CHECK_FALSE(memo.find(1, Vec2(-123.25, 456.5), h));
}
