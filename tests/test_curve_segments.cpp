// Curve discretisation (paper 2.1): unit-mesh segment counts, valid small loops, segments by size and not by wobble.
#include <catch2/catch.hpp>

#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>

#include <algorithm>
#include <cmath>

#include "cad/occt_model.h"
#include "mesher/discretise_curves.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "sizing/size_query.h"
#include "tests/mesher_checks.h"
#include "tests/stage_runs.h"

using namespace sizemesh;
using test::GradedSize;
using test::require_valid_closed;

TEST_CASE("curve segment counts follow the unit mesh rule (Eq. 1a, 2a)", "[mesher]") {
  const Model box = model_from_shape(BRepPrimAPI_MakeBox(1.0, 2.0, 3.0).Shape());
  const UniformSize h(0.3);
  const CurveMesh cm = discretise_curves(box, h);
  for (int c = 1; c <= box.num_curves(); ++c) {
    const int n = static_cast<int>(cm.curves[c].node.size()) - 1;
    CHECK(n == std::max(1L, std::lround(box.curve_length(c) / 0.3)));  // Eq. 2a, h constant
    // Shared end points: the nodes at t0 and t1 are the B-rep points' nodes.
    CHECK(cm.curves[c].node.front() == cm.point_node[box.curve_start_point(c)]);
    CHECK(cm.curves[c].node.back() == cm.point_node[box.curve_end_point(c)]);
  }

  // A linear size along an edge: n = l ln(h1/h0) / (h1 - h0) (Eq. 2a), and
  // every segment has unit metric length (Eq. 1b, 2b).
  const GradedSize graded(box, Vec3(0, 0, 0), 0.05, 0.5, 10.0);
  const CurveMesh cg = discretise_curves(box, graded);
  int checked = 0;
  for (int c = 1; c <= box.num_curves(); ++c) {
    const Vec3 a = box.point_xyz(box.curve_start_point(c)), b = box.point_xyz(box.curve_end_point(c));
    if (a.norm() > 1e-12 && b.norm() > 1e-12) continue;  // only edges from the origin are linear in h
    const double l = (b - a).norm(), h0 = 0.05, h1 = 0.05 + 0.5 * l;
    const double n_exact = l * std::log(h1 / h0) / (h1 - h0);
    const int n = static_cast<int>(cg.curves[c].node.size()) - 1;
    CHECK(n == std::lround(n_exact));
    for (int i = 0; i < n; ++i) {
      const Vec3 p = cg.xyz[cg.curves[c].node[i]], q = cg.xyz[cg.curves[c].node[i + 1]];
      const double hp = graded.at_xyz(p), hq = graded.at_xyz(q);
      const double metric = (q - p).norm() * std::log(hq / hp) / (hq - hp);  // Eq. 2b
      CHECK(metric == Approx(n_exact / n).epsilon(0.02));
    }
    ++checked;
  }
  CHECK(checked == 3);
}

TEST_CASE("closed curves and small loops get enough segments for a valid loop", "[mesher]") {
  // A cylinder thinner than h: its circles still get 3 or more segments.
  const Model cyl = model_from_shape(BRepPrimAPI_MakeCylinder(0.1, 1.0).Shape());
  const UniformSize h(0.5);
  const CurveMesh cm = discretise_curves(cyl, h);
  for (int c = 1; c <= cyl.num_curves(); ++c) {
    if (cyl.curve_degenerated(c)) {
      CHECK(cm.curves[c].node.empty());
      continue;
    }
    if (cyl.curve_start_point(c) == cyl.curve_end_point(c) && cyl.curve_length(c) < 1.0)
      CHECK(cm.curves[c].node.size() >= 4);
  }
  const SurfaceMesh m = mesh_surface(cyl, h);
  const MeshQuality q = mesh_quality(m, cyl, h);
  require_valid_closed(cyl, m, q, 1.0);
}

TEST_CASE("a curve that wobbles far below its elements gets segments by its size, not by its samples' turning", "[mesher][models]") {
  // The 777's fin root and tip sections from OpenVSP: sampled finely, their
  // tangents turn back and forth by tens of radians in all, thousandths of
  // a foot across. At 60 degrees a segment, that turning asked for up to
  // five times the segments their size does.
  const auto run = test::run_until(test::run_options("b777_nosplit_openvsp.stp"), "size_query");
  const Model& model = *run->model;
  const SizeQuery& query = *run->query;
  const CurveMesh cm = discretise_curves(model, query);
  int wobbly = 0;
  for (int c = 1; c <= model.num_curves(); ++c) {
    if (model.curve_degenerated(c)) continue;
    double t0, t1;
    model.curve_range(c, t0, t1);
    const int m = 400;
    double turning = 0, metric = 0;  // Eq. 1a's integral of ds/h
    Vec3 before = model.eval_curve(c, t0), prev = Vec3::Zero();
    for (int k = 1; k <= m; ++k) {
      const Vec3 p = model.eval_curve(c, t0 + (t1 - t0) * k / m);
      Vec3 d = p - before;
      metric += d.norm() / query.at_xyz(0.5 * (p + before));
      before = p;
      if (!(d.norm() > 0)) continue;
      d.normalize();
      if (prev.norm() > 0) turning += std::acos(std::clamp(prev.dot(d), -1.0, 1.0));
      prev = d;
    }
    if (turning < 20) continue;
    ++wobbly;
    const int n = static_cast<int>(cm.curves[c].node.size()) - 1;
    INFO("curve " << c << ": samples turn " << turning << " rad, metric length " << metric << ", " << n << " segments");
    CHECK(n <= 2 * metric + 3);
  }
  CHECK(wobbly >= 2);
}
