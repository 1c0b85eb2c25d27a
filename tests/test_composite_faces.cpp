// Composite faces (topology/, mesher/composite_remesh.h): faces joined across
// smooth curves are meshed as one, so narrow faces and short curves of the
// CAD's topology leave no sliver and no node on the curves they add, while
// real sharp edges keep their nodes on the curve.
#include <catch2/catch.hpp>

#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepAlgoAPI_Splitter.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <Geom_BSplineCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <gp_Pln.hxx>

#include <cmath>
#include <memory>
#include <set>

#include "cad/occt_model.h"
#include "core/predicates.h"
#include "tests/mesher_checks.h"
#include "tests/stage_runs.h"

using namespace sizemesh;

namespace {

// A unit box cut at x = 1 - w: its top, bottom, front and back each a wide
// face and a strip w wide; the cut's curves are smooth (virtual).
TopoDS_Shape box_with_strip(double w) {
  const TopoDS_Shape a = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 1 - w, 1, 1).Shape();
  const TopoDS_Shape b = BRepPrimAPI_MakeBox(gp_Pnt(1 - w, 0, 0), w, 1, 1).Shape();
  return BRepAlgoAPI_Fuse(a, b).Shape();
}

// A cylinder (radius 1, height 2) whose side is cut into n faces, each cap
// into n sectors, by planes through its axis.
TopoDS_Shape sliced_cylinder(int n) {
  const TopoDS_Shape c = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 1, 2).Shape();
  if (n == 0) return c;
  TopTools_ListOfShape args, tools;
  args.Append(c);
  for (int i = 0; i < n; ++i) {
    const double a = kPi * i / n;  // half-planes would do; full planes through the axis cut both sides
    if (2 * i >= n) break;
    tools.Append(BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, 0), gp_Dir(std::cos(a + kPi / 2), std::sin(a + kPi / 2), 0)),
                                         -2, 2, -1, 3).Face());
  }
  BRepAlgoAPI_Splitter split;
  split.SetArguments(args);
  split.SetTools(tools);
  split.Build();
  // The wedges fused again: one solid, its side in n faces, each cap in n sectors.
  TopTools_ListOfShape first, rest;
  for (TopExp_Explorer ex(split.Shape(), TopAbs_SOLID); ex.More(); ex.Next())
    (first.IsEmpty() ? first : rest).Append(ex.Current());
  BRepAlgoAPI_Fuse fuse;
  fuse.SetArguments(first);
  fuse.SetTools(rest);
  fuse.Build();
  return fuse.Shape();
}

// The command's stages on the box with a strip 0.01 wide, h_max 0.1.
std::unique_ptr<RunResult> box_run(bool composite) {
  RunOptions o;
  o.verbose = false;
  o.sizing.h_max = 0.1;
  o.sizing.composite = composite;
  return test::run_model(model_from_shape(box_with_strip(0.01)), o);
}

// Mesh nodes inside the strip's inner curve (x = 0.99 on the top, ends left out).
int nodes_on_inner_curve(const SurfaceMesh& m) {
  int n = 0;
  for (const Vec3& x : m.xyz)
    n += std::abs(x.z() - 1) < 1e-9 && std::abs(x.x() - 0.99) < 1e-6 && x.y() > 1e-9 && x.y() < 1 - 1e-9;
  return n;
}

}  // namespace

TEST_CASE("a strip a tenth of the size wide on a box's top is meshed with the rest of the top") {
  const auto run = box_run(true);
  const SurfaceMesh& m = run->mesh;
  REQUIRE(m.failures.empty());
  int on_top = 0, thin_on_top = 0;
  for (const auto& tr : m.tris) {
    bool top = true;
    for (int n : tr) top = top && std::abs(m.xyz[n].z() - 1) < 1e-9;
    if (!top) continue;
    ++on_top;
    thin_on_top += min_angle_deg(m.xyz[tr[0]], m.xyz[tr[1]], m.xyz[tr[2]]) < 30;
  }
  const int on_inner_curve = nodes_on_inner_curve(m);
  INFO(m.tris.size() << " triangles, " << on_top << " on the top, " << thin_on_top << " of them under 30 degrees, "
                     << on_inner_curve << " nodes on the strip's inner curve");
  CHECK(run->topology.composites == 6);  // the box's six sides
  // The cut's four curves are crossed because each bounds a strip narrower than the size.
  const VirtualReasons& why = run->report.virtual_reasons;
  CHECK(run->topology.count(CurveKind::Virtual) == 4);
  CHECK(why.narrow_face == 4);
  CHECK(why.short_curve + why.small_angle + why.smooth == 0);
  CHECK(thin_on_top == 0);
  CHECK(on_inner_curve == 0);
  test::require_valid_closed(*run->model, m, run->report.quality, run->model->info().diagonal());
  CHECK(run->report.quality.self_intersections == 0);
}

TEST_CASE("a cylinder cut into 20 narrow faces meshes as one") {
  RunOptions o;
  o.verbose = false;
  const auto whole = test::run_model(model_from_shape(sliced_cylinder(0)), o);
  const auto sliced = test::run_model(model_from_shape(sliced_cylinder(20)), o);
  const MeshQuality& q = sliced->report.quality;
  INFO(sliced->mesh.tris.size() << " triangles vs " << whole->mesh.tris.size() << " uncut; " << q.below_24 << " under 24 degrees, "
                                << sliced->report.composite.virtual_nodes_left << " nodes left on cut curves");
  CHECK(sliced->model->num_faces() >= 22);
  CHECK(sliced->topology.composites == 3);
  const VirtualReasons& why = sliced->report.virtual_reasons;  // each crossed curve counted once
  CHECK(why.short_curve + why.narrow_face + why.small_angle + why.smooth == sliced->topology.count(CurveKind::Virtual));
  CHECK(q.below_12 == 0);
  CHECK(q.below_24 <= 0.005 * q.triangles);
  CHECK(std::abs(double(sliced->mesh.tris.size()) / whole->mesh.tris.size() - 1) < 0.15);
  test::require_valid_closed(*sliced->model, sliced->mesh, q, sliced->model->info().diagonal());
  CHECK(q.self_intersections == 0);
}

namespace {

// A straight wing: a 12%-thick symmetric profile of chord 1 (upper and lower
// skins, each one B-spline, meeting smoothly at the leading edge and at 14
// degrees at the trailing edge), extruded 2 along y.
TopoDS_Shape straight_wing() {
  auto skin = [](double side) {
    TColgp_Array1OfPnt p(1, 21);
    for (int i = 0; i <= 20; ++i) {
      const double x = 0.5 * (1 - std::cos(kPi * i / 20));  // leading edge at x = 0, trailing at 1
      const double t = 0.6 * (0.2969 * std::sqrt(x) - 0.126 * x - 0.3516 * x * x + 0.2843 * x * x * x - 0.1036 * x * x * x * x);
      p(i + 1) = gp_Pnt(x, 0, side * t);
    }
    return GeomAPI_PointsToBSpline(p, 3, 8, GeomAbs_C2, 1e-7).Curve();
  };
  const TopoDS_Edge upper = BRepBuilderAPI_MakeEdge(skin(1));
  const TopoDS_Edge lower = BRepBuilderAPI_MakeEdge(skin(-1));
  const TopoDS_Wire wire = BRepBuilderAPI_MakeWire(upper, lower);
  const TopoDS_Face profile = BRepBuilderAPI_MakeFace(wire, true);
  return BRepPrimAPI_MakePrism(profile, gp_Vec(0, 2, 0)).Shape();
}

// The length of the mesh edges lying on the segment a-b (both ends within
// tol of it): the whole segment when the mesh keeps nodes along it.
double length_along(const SurfaceMesh& m, const Vec3& a, const Vec3& b, double tol) {
  const Vec3 d = (b - a).normalized();
  auto on = [&](const Vec3& x) {
    const double s = (x - a).dot(d);
    return s >= -tol && s <= (b - a).norm() + tol && (x - a - s * d).norm() <= tol;
  };
  std::set<std::pair<int, int>> seen;
  double total = 0;
  for (const auto& tr : m.tris)
    for (int k = 0; k < 3; ++k) {
      const int p = tr[k], q = tr[(k + 1) % 3];
      if (on(m.xyz[p]) && on(m.xyz[q]) && seen.insert(std::minmax(p, q)).second) total += (m.xyz[p] - m.xyz[q]).norm();
    }
  return total;
}

}  // namespace

TEST_CASE("real sharp edges keep their nodes: a box's edges and a wing's trailing edge") {
  const auto box = box_run(true);
  // The twelve edges of the unit box, each covered by mesh edges end to end.
  for (int axis = 0; axis < 3; ++axis)
    for (int i = 0; i < 4; ++i) {
      Vec3 a = Vec3::Zero();
      a[(axis + 1) % 3] = i & 1;
      a[(axis + 2) % 3] = (i >> 1) & 1;
      Vec3 b = a;
      b[axis] = 1;
      INFO("box edge from " << a.transpose() << " to " << b.transpose());
      CHECK(length_along(box->mesh, a, b, 1e-9) == Approx(1.0).epsilon(1e-9));
    }
  RunOptions o;
  o.verbose = false;
  o.sizing.h_max = 0.1;
  const auto wing = test::run_model(model_from_shape(straight_wing()), o);
  const Topology& t = wing->topology;
  CHECK(t.count(CurveKind::Angle) >= 1);  // the trailing edge at least
  CHECK(wing->report.quality.below_12 - wing->report.quality.feature_corner_below_12 == 0);
  CHECK(length_along(wing->mesh, Vec3(1, 0, 0), Vec3(1, 2, 0), 1e-6) == Approx(2.0).epsilon(1e-6));
  test::require_valid_closed(*wing->model, wing->mesh, wing->report.quality, wing->model->info().diagonal());
}

TEST_CASE("without composite faces (--no-composite) every B-rep face is meshed apart") {
  const auto run = box_run(false);
  const SurfaceMesh& m = run->mesh;
  REQUIRE(m.failures.empty());
  CHECK_FALSE(run->topology.enabled);
  CHECK(run->topology.composites == run->model->num_faces());
  CHECK(run->report.composite.collapsed + run->report.composite.smoothed + run->report.composite.flipped == 0);
  CHECK(nodes_on_inner_curve(m) > 0);  // the strip's inner curve keeps its nodes
}
