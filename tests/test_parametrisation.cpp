// Parametrisations seen through: a strip collapsed onto a line, a cone's quadratic tip, strongly varying uv speeds.
#include <catch2/catch.hpp>

// GCC takes NCollection_Array2's row table, indexed from its lower bound, for out of bounds once inlined.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"
#include <BRepBuilderAPI_MakeFace.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>

#include "cad/occt_model.h"
#include "core/size_field.h"
#include "mesher/face_surface.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "mesher/uv_stretch.h"
#include "tests/distorted_rectangle.h"

using namespace sizemesh;
using test::DistortedRectangle;

namespace {

// One face on the whole of s, as written: not sewn, not united, not split at its knots.
Model as_written(const Handle(Geom_BSplineSurface)& s) {
  LoadOptions as_read;
  as_read.sew = false;
  as_read.unite = false;
  return model_from_shape(BRepBuilderAPI_MakeFace(s, 1e-7).Face(), as_read);
}

}  // namespace

TEST_CASE("a point beside a strip collapsed onto a line is found on the surface from a start on the strip", "[mesher]") {
  // A ruled B-spline whose v in [0, 1] lies on one line (as an exporter
  // writes a sharp trailing edge into a wing's surface) and which runs out
  // to a second line over v in [1, 2]. On the strip every v is one point:
  // Newton started there cannot move in v, and the whole face's nearest
  // point is taken instead.
  TColgp_Array2OfPnt poles(1, 2, 1, 3);
  for (int i = 1; i <= 2; ++i) {
    const double x = 10.0 * (i - 1);
    poles(i, 1) = gp_Pnt(x, 0, 0);
    poles(i, 2) = gp_Pnt(x, 0, 0);
    poles(i, 3) = gp_Pnt(x, 5, 1);
  }
  TColStd_Array1OfReal uk(1, 2), vk(1, 3);
  TColStd_Array1OfInteger um(1, 2), vm(1, 3);
  uk(1) = 0, uk(2) = 1, um(1) = um(2) = 2;
  vk(1) = 0, vk(2) = 1, vk(3) = 2, vm(1) = vm(3) = 2, vm(2) = 1;
  Handle(Geom_BSplineSurface) strip = new Geom_BSplineSurface(poles, uk, vk, um, vm, 1, 1);
  const Model model = as_written(strip);
  REQUIRE(model.num_faces() == 1);
  const Vec3 x(4, 2.5, 0.5);  // S(0.4, 1.5)
  Vec2 uv(0.4, 0.5);
  REQUIRE(model.eval_face(1, uv).du.norm() > 0);
  REQUIRE(model.eval_face(1, uv).dv.norm() == 0);
  Vec2 newton = uv;
  const bool stalled = !model.project_to_face(1, x, newton) || (model.eval_face(1, newton).p - x).norm() > 1;
  CHECK(stalled);
  REQUIRE(model.nearest_on_face(1, x, uv));
  CHECK((model.eval_face(1, uv).p - x).norm() < 1e-9);
  CHECK(uv.y() == Approx(1.5).margin(1e-9));
}

TEST_CASE("a cone closing in quadratically to its tip meshes with triangles of the size at the tip, none turned over", "[mesher]") {
  // Degree 2 along u, its last two rows of poles both on the tip: S_u and
  // S_v vanish there together (as an OpenVSP fuselage's tail cone written to
  // end in a point), so the metric on the pole line is zero both ways. The
  // front's ideal point off the pole is placed one size from the tip in
  // space; taken in the pole's metric it ran off the surface and the tip's
  // fan spanned the cone.
  const int ring = 9;  // a square ring in v, closed (last pole = first)
  TColgp_Array2OfPnt poles(1, 3, 1, ring);
  for (int j = 1; j <= ring; ++j) {
    const double a = 2 * M_PI * (j - 1) / (ring - 1);
    poles(1, j) = gp_Pnt(0, 2 * std::cos(a), 2 * std::sin(a));
    poles(2, j) = gp_Pnt(4, 0, 0);
    poles(3, j) = gp_Pnt(4, 0, 0);
  }
  TColStd_Array1OfReal uk(1, 2), vk(1, ring);
  TColStd_Array1OfInteger um(1, 2), vm(1, ring);
  uk(1) = 0, uk(2) = 1, um(1) = um(2) = 3;
  for (int j = 1; j <= ring; ++j) vk(j) = j - 1, vm(j) = 1;
  vm(1) = vm(ring) = 2;
  Handle(Geom_BSplineSurface) cone = new Geom_BSplineSurface(poles, uk, vk, um, vm, 2, 1);
  const Model model = as_written(cone);
  REQUIRE(model.num_faces() == 1);
  REQUIRE(model.eval_face(1, Vec2(1, 0.5)).du.norm() < 1e-12);  // the tip: no length along u
  const double h = 0.25;
  const UniformSize size(h);
  const SurfaceMesh m = mesh_surface(model, size);
  REQUIRE(m.failures.empty());
  const MeshQuality q = mesh_quality(m, model, size);
  CHECK(q.inverted == 0);
  // Every edge at the tip within twice the size.
  const Vec3 tip(4, 0, 0);
  int at_tip = 0;
  for (const auto& t : m.tris)
    for (int k = 0; k < 3; ++k) {
      const Vec3 &a = m.xyz[t[k]], &b = m.xyz[t[(k + 1) % 3]];
      if ((a - tip).norm() > 1e-9) continue;
      ++at_tip;
      CHECK((b - a).norm() < 2 * h);
    }
  CHECK(at_tip >= 3);
}

TEST_CASE("a distorted parametrisation gives a mesh shaped in space, not in uv", "[mesher]") {
  // |du| varies 58:1 and |dv| 19:1 across the face: equilateral triangles in
  // uv would be slivers in space; the metric (and, where it is not enough, the
  // ideal point placed in space) keeps them well shaped on the surface.
  const DistortedRectangle rect(4.0, 1.0);
  const UniformSize h(0.1);
  const SurfaceMesh m = mesh_surface(rect, h);
  const MeshQuality q = mesh_quality(m, rect, h);
  INFO("triangles " << q.triangles << ", below 12 deg " << q.below_12 << ", below 24 deg " << q.below_24
                    << ", conformity " << q.size_conformity << ", ideal points placed in space "
                    << m.stats.fronts_3d);
  REQUIRE(m.failures.empty());
  CHECK(q.inverted == 0);
  CHECK(q.zero_area == 0);
  CHECK(q.nonmanifold_edges == 0);
  CHECK(q.boundary_edges == static_cast<int>(std::lround(2 * (4.0 + 1.0) / 0.1)));
  CHECK(q.area == Approx(4.0).epsilon(1e-9));
  CHECK(q.below_12 == 0);
  CHECK(q.below_24 <= 0.005 * q.triangles);
  CHECK(q.size_conformity >= 0.95);
}

TEST_CASE("a parametrisation whose speed varies strongly is stretched towards arc length", "[mesher]") {
  SECTION("speed falling to zero at an edge: the map and its inverse") {
    // The manta's body patches end at the trailing edge with |du| = 0: in the
    // surface's own uv the front put nodes a hundredth of h from that edge.
    const DistortedRectangle rect(4.0, 1.0, true);
    const UvStretch stretch(rect, 1);
    CHECK(stretch.stretched(0));
    CHECK_FALSE(stretch.stretched(1));  // |dv| varies 19:1, under UvStretch::kRatio
    for (double w : {0.0, 0.1, 0.5, 0.9, 0.99, 1.0}) {
      const Vec2 uv = stretch.to_surface(Vec2(w, 0.3));
      CHECK(uv.y() == 0.3);
      CHECK(stretch.to_mesher(uv).x() == Approx(w).margin(1e-12));
    }
    CHECK(stretch.to_surface(Vec2(0, 0)).x() == 0.0);
    CHECK(stretch.to_surface(Vec2(1, 0)).x() == 1.0);
    // About arc length: the middle of the mesher's range is near the middle
    // of the face in space (x = 2), where the surface's own u = 0.5 is at x = 3.
    CHECK(rect.eval_face(1, stretch.to_surface(Vec2(0.5, 0.5))).p.x() == Approx(2.0).epsilon(0.02));
    // The samples' derivatives are taken in the mesher's uv.
    const UniformSize h(0.1);
    FaceSurface fs(rect, h, 1);
    for (double w : {0.2, 0.5, 0.8}) {
      const Vec2 p(w, 0.4), e(1e-6, 0);
      const Vec3 fd = (fs.eval_shape(p + e).p - fs.eval_shape(p - e).p) / 2e-6;
      CHECK((fs.eval_shape(p).du - fd).norm() <= 1e-6 * fd.norm());
    }
  }
  SECTION("speed varying 58:1 on a sheared face: well-sized elements") {
    // u-lines run obliquely (y += 2x) and |du| grows 58-fold along them: in the
    // surface's own uv the front made edges about twice the wanted length.
    const DistortedRectangle rect(4.0, 1.0, false, 2.0);
    const UniformSize h(0.1);
    const SurfaceMesh m = mesh_surface(rect, h);
    const MeshQuality q = mesh_quality(m, rect, h);
    INFO("triangles " << q.triangles << ", below 12 deg " << q.below_12 << ", below 24 deg " << q.below_24
                      << ", conformity " << q.size_conformity);
    REQUIRE(m.failures.empty());
    CHECK(q.inverted == 0);
    CHECK(q.zero_area == 0);
    CHECK(q.boundary_edges == 2 * std::lround(4.0 * std::hypot(1.0, 2.0) / 0.1) + 2 * 10);
    CHECK(q.area == Approx(4.0).epsilon(1e-9));
    CHECK(q.below_12 == 0);
    CHECK(q.below_24 <= 0.005 * q.triangles);
    CHECK(q.size_conformity >= 0.95);
    // The mesh leaves in the surface's own uv: every corner's uv maps to its node.
    double worst = 0;
    for (size_t t = 0; t < m.tris.size(); ++t)
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, (rect.eval_face(1, m.tri_uv[t][k]).p - m.xyz[m.tris[t][k]]).norm());
    CHECK(worst <= 1e-9);
  }
}

TEST_CASE("a B-spline whose speed jumps at its knots is stretched to arc length exactly, span by span", "[mesher]") {
  // Degree 1 along v with spans 4 times shorter each, down to 1/4096 and
  // back (OpenVSP writes a fairing's rounded corner so): the speed is
  // constant in each span and jumps by 4 at every knot. Map intervals that
  // straddled a knot averaged the two sides and left the smallest spans
  // several times too narrow or wide for the front's metric.
  const std::vector<double> spans = {1, 0.25, 1.0 / 16, 1.0 / 64, 1.0 / 256, 1.0 / 1024, 1.0 / 4096,
                                     1.0 / 256, 1.0 / 16, 1};
  const int n = static_cast<int>(spans.size());
  TColgp_Array2OfPnt poles(1, 2, 1, n + 1);
  double x = 0;
  for (int j = 1; j <= n + 1; ++j) {
    poles(1, j) = gp_Pnt(x, 0, 0);
    poles(2, j) = gp_Pnt(x, 0, 1);
    if (j <= n) x += spans[j - 1];
  }
  const double length = x;
  TColStd_Array1OfReal uk(1, 2), vk(1, n + 1);
  TColStd_Array1OfInteger um(1, 2), vm(1, n + 1);
  uk(1) = 0, uk(2) = 1, um(1) = um(2) = 2;
  for (int j = 1; j <= n + 1; ++j) vk(j) = j - 1, vm(j) = 1;
  vm(1) = vm(n + 1) = 2;
  Handle(Geom_BSplineSurface) s = new Geom_BSplineSurface(poles, uk, vk, um, vm, 1, 1);
  const Model model = as_written(s);
  REQUIRE(model.num_faces() == 1);
  REQUIRE(model.face_knots(1, 1).size() == static_cast<size_t>(n - 1));
  const UVBox box = model.face_uv_bounds(1);
  REQUIRE(box.lo.y() == 0.0);
  REQUIRE(box.hi.y() == static_cast<double>(n));
  const UvStretch stretch(model, 1);
  CHECK_FALSE(stretch.stretched(0));
  REQUIRE(stretch.stretched(1));
  // In the mesher's v every span moves at the same speed in space: the
  // length over the range, inside the shortest span too.
  const double want = length / n;
  double worst = 0;
  int samples = 0;
  for (int j = 0; j < n; ++j)
    for (double f : {0.2, 0.5, 0.8}) {
      // The point at fraction f of span j, in the mesher's v.
      double before = 0;
      for (int k = 0; k < j; ++k) before += spans[k];
      const double w = (before + f * spans[j]) / want, e = 1e-4 * spans[j] / want;
      const Vec3 a = model.eval_face(1, stretch.to_surface(Vec2(0.5, w - e))).p;
      const Vec3 b = model.eval_face(1, stretch.to_surface(Vec2(0.5, w + e))).p;
      worst = std::max(worst, std::abs((b - a).norm() / (2 * e) / want - 1));
      ++samples;
    }
  CHECK(samples == 3 * n);
  CHECK(worst <= 1e-6);
}
