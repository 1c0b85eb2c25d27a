// Surface mesher (paper 4.1): unit-mesh curve counts (paper 2.1), and on OCCT
// solids and the shared models: no face fails, closed solids give watertight
// and consistently oriented meshes with no inverted or zero-area triangle,
// nodes on their surfaces, the CAD area, good angles, sizes that conform, and
// a mesh independent of the thread count.
#include <catch2/catch.hpp>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <ElCLib.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <gp_Circ.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Ax2.hxx>

#include <algorithm>
#include <functional>
#include <cmath>
#include <set>
#include <string>

#include "background/background_mesh.h"
#include "cad/occt_model.h"
#include "core/predicates.h"
#include "mesher/discretise_curves.h"
#include "mesher/mesh_surface.h"
#include "mesher/optimise.h"
#include "mesher/quality.h"
#include "mesher/uv_stretch.h"
#include "mesher/face_surface.h"
#include "sizing/refine_background.h"
#include "sizing/size_query.h"
#include "sizing/smooth.h"
#include "tests/stage_runs.h"
#include "tests/test_models.h"

using namespace sizemesh;

namespace {

constexpr double kPi = 3.14159265358979323846;

// h grows linearly with the distance from a point, clamped to [h0, h_max].
class GradedSize final : public SizeField {
 public:
  GradedSize(const Geometry& g, Vec3 center, double h0, double slope, double h_max)
      : g_(g), c_(center), h0_(h0), slope_(slope), h_max_(h_max) {}
  double at(int face, const Vec2& uv, int&) const override { return at_xyz(g_.eval_face(face, uv).p); }
  double at_xyz(const Vec3& x) const override {
    return std::min(h_max_, h0_ + slope_ * (x - c_).norm());
  }

 private:
  const Geometry& g_;
  Vec3 c_;
  double h0_, slope_, h_max_;
};

double cad_area(const Geometry& g) {
  double a = 0;
  for (int f = 1; f <= g.num_faces(); ++f) a += g.face_area(f);
  return a;
}

// Every property the mesher promises for a closed solid.
void require_valid_closed(const Geometry& g, const SurfaceMesh& m, const MeshQuality& q, double diag,
                          bool closed = true, const test::SharedModel& known = {}) {
  INFO("failures " << m.failures.size() << (m.failures.empty() ? "" : ": " + m.failures[0].reason));
  REQUIRE(m.failures.empty());
  REQUIRE(q.triangles > 0);
  if (closed) {
    CHECK(q.boundary_edges == 0);
    CHECK(q.nonmanifold_edges == 0);
  }
  if (known.consistent_orientation) CHECK(q.orientation_conflicts == 0);
  CHECK(q.inverted <= known.max_inverted_share * q.triangles);
  CHECK(q.zero_area == 0);
  CHECK(q.max_inner_node_distance <= 1e-9 * diag);
  CHECK(q.max_node_distance <= 1e-3 * diag);  // curve nodes: within the CAD's edge tolerance
}

void require_good_shape(const MeshQuality& q, const SurfaceMesh& m, const Geometry& g) {
  INFO("triangles " << q.triangles << ", below 12 deg " << q.below_12 << ", below 24 deg " << q.below_24
                    << ", conformity " << q.size_conformity << ", area " << q.area << " vs CAD "
                    << cad_area(g));
  CHECK(q.below_12 <= 0.0005 * q.triangles);
  CHECK(q.below_24 <= 0.005 * q.triangles);
  CHECK(q.size_conformity >= 0.90);
  CHECK(std::abs(q.area - cad_area(g)) <= 0.005 * cad_area(g));
}

TopoDS_Shape plate_with_hole() {
  TopoDS_Shape plate = BRepPrimAPI_MakeBox(gp_Pnt(-2, -2, 0), 4, 4, 0.5).Shape();
  TopoDS_Shape hole = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0.3, 0.2, -1), gp_Dir(0, 0, 1)), 0.8, 3).Shape();
  return BRepAlgoAPI_Cut(plate, hole).Shape();
}

// Two fused cylinders, the thinner one tangent to the thicker one's side: the
// hole it cuts touches the thicker face's outer loop at one point.
TopoDS_Shape tangent_cylinders() {
  TopoDS_Shape a = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -2), gp_Dir(0, 0, 1)), 0.5, 4).Shape();
  TopoDS_Shape b = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-2, 0.2, 0), gp_Dir(1, 0, 0)), 0.3, 4).Shape();
  return BRepAlgoAPI_Fuse(a, b).Shape();
}

struct Solid {
  const char* name;
  TopoDS_Shape shape;
  double h;
};

std::vector<Solid> solids() {
  return {
      {"box", BRepPrimAPI_MakeBox(1.0, 2.0, 0.5).Shape(), 0.1},
      {"sphere", BRepPrimAPI_MakeSphere(1.0).Shape(), 0.1},
      {"cylinder", BRepPrimAPI_MakeCylinder(1.0, 2.0).Shape(), 0.1},
      {"torus", BRepPrimAPI_MakeTorus(2.0, 0.5).Shape(), 0.06},
      {"cone", BRepPrimAPI_MakeCone(1.0, 0.0, 2.0).Shape(), 0.08},
      {"plate with a hole", plate_with_hole(), 0.12},
      {"tangent cylinders", tangent_cylinders(), 0.07},
  };
}

}  // namespace

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
  LoadOptions as_read;  // the surface as written, not repaired
  as_read.sew = false;
  as_read.unite = false;
  const Model model = model_from_shape(BRepBuilderAPI_MakeFace(strip, 1e-7).Face(), as_read);
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
  LoadOptions as_read;  // the surface as written, not split at its knots
  as_read.sew = false;
  as_read.unite = false;
  const Model model = model_from_shape(BRepBuilderAPI_MakeFace(cone, 1e-7).Face(), as_read);
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

TEST_CASE("a sharp corner gets one thin triangle: long first segments where its wedge is a quarter element wide", "[mesher]") {
  // A prism over a triangle whose apex angle is 4 degrees: with equal steps
  // of h along both sides, the first ~6 triangles of each cap's wedge are
  // under 12 degrees; with the long first segments only the apex triangle is.
  const double half = 3.5, len = 100, h = 2;
  BRepBuilderAPI_MakePolygon profile(gp_Pnt(0, 0, 0), gp_Pnt(len, half, 0), gp_Pnt(len, -half, 0), true);
  const TopoDS_Shape prism =
      BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(profile.Wire()).Face(), gp_Vec(0, 0, 20)).Shape();
  const Model model = model_from_shape(prism);
  const UniformSize size(h);
  const double alpha = 2 * std::atan(half / len);
  const double r = 0.25 * h / std::tan(alpha);  // the wedge is h/4 wide there
  const CurveMesh cm = discretise_curves(model, size);
  int long_sides = 0;
  for (int c = 1; c <= model.num_curves(); ++c) {
    const auto& nodes = cm.curves[c].node;
    if (std::abs(model.curve_length(c) - std::hypot(len, half)) > 1e-6) continue;
    ++long_sides;
    // The node next to the apex (x = 0) is r away from it, the others about h apart.
    const bool apex_first = cm.xyz[nodes.front()].x() < 1e-9;
    const Vec3 apex = cm.xyz[apex_first ? nodes.front() : nodes.back()];
    const Vec3 next = cm.xyz[apex_first ? nodes[1] : nodes[nodes.size() - 2]];
    CHECK((next - apex).norm() == Approx(r).epsilon(1e-3));
    const int ordinary = static_cast<int>(nodes.size()) - 2;
    CHECK(ordinary == static_cast<int>(std::lround((model.curve_length(c) - r) / h)));
  }
  CHECK(long_sides == 4);
  const SurfaceMesh m = mesh_surface(model, size);
  const MeshQuality q = mesh_quality(m, model, size);
  require_valid_closed(model, m, q, 1.0);
  CHECK(q.below_12 == 2);  // one apex triangle per cap, with the CAD's 4 degrees
  CHECK(q.forced_below_12 == 2);
  CHECK(q.worst_angle == Approx(alpha * 180 / 3.14159265358979323846).epsilon(0.02));
}

TEST_CASE("a rounded edge narrower than the elements is closed across, with no point inside it", "[mesher]") {
  // A slab whose two ends are half cylinders of radius r: each end is a strip
  // 2r wide whose normal turns half round, ten times narrower than h tan(12
  // deg). No chord across it faces both sides' normals; the front alone
  // would fill it with points of its own.
  const double r = 0.005, len = 4, height = 2, h = 0.5;
  auto arc = [](gp_Pnt a, gp_Pnt m, gp_Pnt b) {
    return BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(a, m, b).Value()).Edge();
  };
  BRepBuilderAPI_MakeWire wire;
  wire.Add(BRepBuilderAPI_MakeEdge(gp_Pnt(0, -r, 0), gp_Pnt(len, -r, 0)).Edge());
  wire.Add(arc(gp_Pnt(len, -r, 0), gp_Pnt(len + r, 0, 0), gp_Pnt(len, r, 0)));
  wire.Add(BRepBuilderAPI_MakeEdge(gp_Pnt(len, r, 0), gp_Pnt(0, r, 0)).Edge());
  wire.Add(arc(gp_Pnt(0, r, 0), gp_Pnt(-r, 0, 0), gp_Pnt(0, -r, 0)));
  const TopoDS_Shape slab =
      BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(wire.Wire()).Face(), gp_Vec(0, 0, height)).Shape();
  const Model model = model_from_shape(slab);
  const UniformSize size(h);
  const SurfaceMesh m = mesh_surface(model, size);
  const MeshQuality q = mesh_quality(m, model, size);
  require_valid_closed(model, m, q, len);
  CHECK(q.inverted == 0);
  int strips = 0;
  for (int f = 1; f <= model.num_faces(); ++f) {
    if (std::abs(model.face_area(f) - M_PI * r * height) > 1e-6) continue;
    ++strips;
    int triangles = 0, inner = 0;
    std::set<int> nodes;
    for (size_t t = 0; t < m.tris.size(); ++t) {
      if (m.tri_face[t] != f) continue;
      ++triangles;
      for (int n : m.tris[t]) inner += m.node_dim[n] == 2, nodes.insert(n);
    }
    // A disc triangulated from its boundary nodes alone.
    CHECK(inner == 0);
    CHECK(triangles == static_cast<int>(nodes.size()) - 2);
  }
  CHECK(strips == 2);
  CHECK(q.below_12 > 0);
  CHECK(q.avoidable_below_12 == 0);
}

TEST_CASE("with a deviation bound, a sharp corner's first segment is no longer than the chord of that height on the faces beside it", "[mesher]") {
  // The 4-degree wedge again, its long sides now arcs of radius 50 bending
  // apart, so the side faces on them are cylinders. A long first segment on
  // an arc spans the cylinder with one chord; with --deviation it is at most
  // the chord of that height there, 2 sqrt(2 R d - d^2).
  const double R = 50, a = 2 * M_PI / 180, theta = 0.5, h = 2;
  const gp_Pnt cu(-R * std::sin(a), R * std::cos(a), 0), cl(-R * std::sin(a), -R * std::cos(a), 0);
  const double up0 = a - M_PI / 2, lo1 = M_PI / 2 - a;  // the apex's angle on each circle
  const gp_Circ upper(gp_Ax2(cu, gp::DZ()), R), lower(gp_Ax2(cl, gp::DZ()), R);
  const TopoDS_Edge e1 = BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(upper, up0, up0 + theta, true).Value()).Edge();
  const TopoDS_Edge e3 = BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(lower, lo1 - theta, lo1, true).Value()).Edge();
  const gp_Pnt pu = ElCLib::Value(up0 + theta, upper), pl = ElCLib::Value(lo1 - theta, lower);
  const TopoDS_Edge e2 = BRepBuilderAPI_MakeEdge(pu, pl).Edge();
  const TopoDS_Wire wire = BRepBuilderAPI_MakeWire(e1, e2, e3).Wire();
  const TopoDS_Shape prism = BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(wire).Face(), gp_Vec(0, 0, 20)).Shape();
  const Model model = model_from_shape(prism);
  REQUIRE(model.info().solids == 1);
  const UniformSize size(h);
  // First segment at the apex of each of the 4 arcs (chord length).
  auto first_segments = [&](double deviation) {
    UniformSize bounded(h);
    AccuracyRules rules;
    rules.deviation = deviation;
    bounded.set_accuracy(rules);
    const CurveMesh cm = discretise_curves(model, bounded);
    std::vector<double> out;
    for (int c = 1; c <= model.num_curves(); ++c) {
      if (std::abs(model.curve_length(c) - R * theta) > 1e-6) continue;
      const auto& nodes = cm.curves[c].node;
      const bool apex_first = std::abs(cm.xyz[nodes.front()].x()) < 1e-9 && std::abs(cm.xyz[nodes.front()].y()) < 1e-9;
      out.push_back((cm.xyz[apex_first ? nodes[1] : nodes[nodes.size() - 2]] -
                     cm.xyz[apex_first ? nodes.front() : nodes.back()]).norm());
    }
    return out;
  };
  const double lead = 0.25 * h / std::tan(2 * a);  // no bound: the wedge is h/4 wide there
  auto chord = [&](double arc) { return 2 * R * std::sin(arc / (2 * R)); };
  for (double d : first_segments(0)) CHECK(d == Approx(chord(lead)).epsilon(2e-3));
  const double cap = 2 * std::sqrt(2 * R * 0.1 - 0.01);  // under the lead
  REQUIRE(cap < lead);
  for (double d : first_segments(0.1)) CHECK(d == Approx(chord(cap)).epsilon(2e-3));
  // A bound whose chord is under h leaves no long first segment at all.
  for (double d : first_segments(0.01)) {
    CHECK(d > 0.9 * h);  // an ordinary step: the arc in equal steps of about h
    CHECK(d < 1.1 * h);
  }
  CHECK(first_segments(0.01).size() == 4);
  UniformSize bounded(h);
  AccuracyRules rules;
  rules.deviation = 0.1;
  bounded.set_accuracy(rules);
  const SurfaceMesh m = mesh_surface(model, bounded, MeshOptions{});
  const MeshQuality q = mesh_quality(m, model, size);
  require_valid_closed(model, m, q, 1.0);
}

TEST_CASE("OCCT solids mesh watertight, valid, on the CAD area, with good angles", "[mesher]") {
  for (const Solid& s : solids()) {
    SECTION(s.name) {
      const Model model = model_from_shape(s.shape);
      const double diag = model.info().diagonal();
      const UniformSize h(s.h);
      const SurfaceMesh m = mesh_surface(model, h);
      const MeshQuality q = mesh_quality(m, model, h);
      INFO(s.name);
      require_valid_closed(model, m, q, diag);
      require_good_shape(q, m, model);
    }
  }
}

TEST_CASE("OCCT solids mesh valid under a graded size map", "[mesher]") {
  for (const Solid& s : solids()) {
    SECTION(s.name) {
      const Model model = model_from_shape(s.shape);
      const double diag = model.info().diagonal();
      const GradedSize h(model, model.info().bbox_min, 0.3 * s.h, 0.3, 2.5 * s.h);
      const SurfaceMesh m = mesh_surface(model, h);
      const MeshQuality q = mesh_quality(m, model, h);
      INFO(s.name);
      require_valid_closed(model, m, q, diag);
      INFO("below 12 deg " << q.below_12 << " of " << q.triangles << ", conformity " << q.size_conformity);
      CHECK(q.below_12 <= 0.0005 * q.triangles);
      CHECK(q.below_24 <= 0.005 * q.triangles);
      CHECK(q.size_conformity >= 0.90);
    }
  }
}

TEST_CASE("the mesh does not depend on the thread count", "[mesher]") {
  const Model model = model_from_shape(plate_with_hole());
  const UniformSize h(0.1);
  MeshOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const SurfaceMesh a = mesh_surface(model, h, one);
  const SurfaceMesh b = mesh_surface(model, h, two);
  CHECK(a.tris == b.tris);
  CHECK(a.xyz == b.xyz);
  CHECK(a.tri_face == b.tri_face);
}

TEST_CASE("the orientation follows the shell: outward normals on a closed solid", "[mesher]") {
  const Model box = model_from_shape(BRepPrimAPI_MakeBox(1.0, 1.0, 1.0).Shape());
  const UniformSize h(0.2);
  const SurfaceMesh m = mesh_surface(box, h);
  const Vec3 center(0.5, 0.5, 0.5);
  for (const auto& t : m.tris) {
    const Vec3 n = (m.xyz[t[1]] - m.xyz[t[0]]).cross(m.xyz[t[2]] - m.xyz[t[0]]);
    const Vec3 c = (m.xyz[t[0]] + m.xyz[t[1]] + m.xyz[t[2]]) / 3.0;
    CHECK(n.dot(c - center) > 0);
  }
  // Signed volume of a closed, outward mesh is the solid's volume.
  double vol = 0;
  for (const auto& t : m.tris) vol += m.xyz[t[0]].dot(m.xyz[t[1]].cross(m.xyz[t[2]])) / 6.0;
  CHECK(vol == Approx(1.0).epsilon(1e-9));
}

TEST_CASE("shared models mesh with no failed face, watertight when closed", "[mesher][models]") {
  for (const auto& c : test::shared_models()) {
    SECTION(c.file) {
      const Model model = load_model(test::model_path(c.file));
      const double diag = model.info().diagonal();
      const UniformSize h(diag / 40);
      MeshOptions one, two;
      one.threads = 1;
      two.threads = 2;
      const SurfaceMesh m = mesh_surface(model, h, two);
      const MeshQuality q = mesh_quality(m, model, h);
      INFO(c.file << ": " << q.triangles << " triangles");
      require_valid_closed(model, m, q, diag, c.closed, c);
      const SurfaceMesh m1 = mesh_surface(model, h, one);
      CHECK(m1.tris == m.tris);
      CHECK(m1.xyz == m.xyz);
    }
  }
}

TEST_CASE("shared models at a resolving size: CAD area, conforming sizes, good angles", "[mesher][models]") {
  // With h = diagonal / 200 the size resolves the models' curvature, so the
  // area and size checks are fair; at diagonal / 40 faces narrower than h and
  // curves shorter than h force short edges and thin triangles whatever the mesher does.
  // Triangles with a corner on a B-rep point or curve can be forced by the
  // CAD (corner angles below 12 degrees, short curves next to long ones, faces
  // narrower than h); triangles inside the faces are the mesher's own.
  struct Case {
    const char* file;
    bool all_angles;  // the CAD allows the angle thresholds on every triangle
  };
  const Case cases[] = {{"onera_m6_wing.stp", false},      {"cone70_capsule_sting.step", true},
                        {"hemisphere_cylinder_domain.stp", true}, {"impeller_laufrad.stp", true},
                        {"cylinder_head_fins.stp", true},  {"steering_knuckle.stp", false},
                        {"d150_fuselage.igs", true},       {"f16_openvsp.stp", false}};
  for (const Case& c : cases) {
    SECTION(c.file) {
      const Model model = load_model(test::model_path(c.file));
      const UniformSize h(model.info().diagonal() / 200);
      const SurfaceMesh m = mesh_surface(model, h);
      const MeshQuality q = mesh_quality(m, model, h);
      REQUIRE(m.failures.empty());
      int inner = 0, inner_12 = 0, inner_24 = 0;
      for (size_t t = 0; t < m.tris.size(); ++t) {
        bool on_curve = false;
        for (int v : m.tris[t]) on_curve = on_curve || m.node_dim[v] < 2;
        if (on_curve) continue;
        ++inner;
        if (q.min_angle[t] < 12) ++inner_12;
        if (q.min_angle[t] < 24) ++inner_24;
      }
      const double area = cad_area(model);
      INFO(c.file << ": " << q.triangles << " triangles, below 12 deg " << q.below_12 << ", below 24 deg "
                  << q.below_24 << "; inside faces " << inner << ", below 12 deg " << inner_12
                  << ", below 24 deg " << inner_24 << "; conformity " << q.size_conformity << "; area "
                  << q.area << " vs CAD " << area);
      CHECK(std::abs(q.area - area) <= 0.005 * area);
      CHECK(q.size_conformity >= 0.90);
      CHECK(inner_12 == 0);
      CHECK(inner_24 <= 0.005 * inner);
      if (c.all_angles) {
        CHECK(q.below_12 <= 0.0005 * q.triangles);
        CHECK(q.below_24 <= 0.005 * q.triangles);
      }
    }
  }
}

namespace {

// A B-rep whose one face cannot be evaluated (the kernel throws there, as the
// geometry layer reports it: EvaluationError), or, with bug set, whose face
// throws what only a programming error would (std::logic_error).
class FaultyFace final : public Geometry {
 public:
  FaultyFace(const Geometry& g, int bad, bool bug = false) : g_(g), bad_(bad), bug_(bug) {}
  int num_faces() const override { return g_.num_faces(); }
  int num_curves() const override { return g_.num_curves(); }
  int num_points() const override { return g_.num_points(); }
  SurfaceD1 eval_face(int face, const Vec2& uv) const override {
    if (face == bad_ && bug_) throw std::logic_error("index out of range");
    if (face == bad_) throw EvaluationError("surface evaluation failed");
    return g_.eval_face(face, uv);
  }
  bool principal_curvatures(int face, const Vec2& uv, double& k1, double& k2) const override {
    return g_.principal_curvatures(face, uv, k1, k2);
  }
  bool face_reversed(int face) const override { return g_.face_reversed(face); }
  UVBox face_uv_bounds(int face) const override { return g_.face_uv_bounds(face); }
  double face_period_u(int face) const override { return g_.face_period_u(face); }
  double face_period_v(int face) const override { return g_.face_period_v(face); }
  double face_area(int face) const override { return g_.face_area(face); }
  double face_boundary_length(int face) const override { return g_.face_boundary_length(face); }
  std::vector<FaceLoop> face_loops(int face) const override { return g_.face_loops(face); }
  bool project_to_face(int face, const Vec3& xyz, Vec2& uv) const override {
    return g_.project_to_face(face, xyz, uv);
  }
  bool nearest_on_face(int face, const Vec3& xyz, Vec2& uv) const override {
    return g_.nearest_on_face(face, xyz, uv);
  }
  void curve_range(int curve, double& t0, double& t1) const override { g_.curve_range(curve, t0, t1); }
  bool curve_degenerated(int curve) const override { return g_.curve_degenerated(curve); }
  Vec3 eval_curve(int curve, double t) const override { return g_.eval_curve(curve, t); }
  Vec3 curve_tangent(int curve, double t) const override { return g_.curve_tangent(curve, t); }
  bool curve_curvature(int curve, double t, double& k) const override { return g_.curve_curvature(curve, t, k); }
  double curve_length(int curve) const override { return g_.curve_length(curve); }
  int curve_start_point(int curve) const override { return g_.curve_start_point(curve); }
  int curve_end_point(int curve) const override { return g_.curve_end_point(curve); }
  Vec2 eval_pcurve(int curve, int face, int side, double t) const override {
    return g_.eval_pcurve(curve, face, side, t);
  }
  Vec3 point_xyz(int point) const override { return g_.point_xyz(point); }

 private:
  const Geometry& g_;
  int bad_;
  bool bug_;
};

// A size map with a hole: no positive size on one side of the model.
class SizeWithHole final : public SizeField {
 public:
  SizeWithHole(const Geometry& g, double h) : g_(g), h_(h) {}
  double at(int face, const Vec2& uv, int&) const override { return at_xyz(g_.eval_face(face, uv).p); }
  double at_xyz(const Vec3& x) const override {
    if (x.x() > 0.6) return std::nan("");
    if (x.x() > 0.4) return 0.0;
    return h_;
  }

 private:
  const Geometry& g_;
  double h_;
};

}  // namespace

TEST_CASE("a face the kernel cannot evaluate is reported and the rest is kept", "[mesher]") {
  const Model box = model_from_shape(BRepPrimAPI_MakeBox(1.0, 1.0, 1.0).Shape());
  const FaultyFace faulty(box, 3);
  const UniformSize h(0.2);
  const SurfaceMesh m = mesh_surface(faulty, h);
  REQUIRE(m.failures.size() == 1);
  CHECK(m.failures[0].face == 3);
  CHECK(!m.failures[0].reason.empty());
  int other_faces = 0;
  for (int f : m.tri_face) {
    CHECK(f != 3);
    other_faces += f != 3;
  }
  CHECK(other_faces > 0);
  // The hole left by the face is exactly its boundary: every other edge is shared.
  const MeshQuality q = mesh_quality(m, faulty, h);
  CHECK(q.nonmanifold_edges == 0);
  CHECK(q.boundary_edges == 4 * 5);  // the face's four sides, 5 segments each
}

TEST_CASE("a programming error while meshing a face ends the run, not passed off as a failed face", "[mesher]") {
  const Model box = model_from_shape(BRepPrimAPI_MakeBox(1.0, 1.0, 1.0).Shape());
  const UniformSize h(0.2);
  CHECK_THROWS_AS(mesh_surface(FaultyFace(box, 3, true), h), std::logic_error);
}

TEST_CASE("a failed face leaves every other face meshed exactly as before, and says why", "[mesher]") {
  for (const TopoDS_Shape& shape : {BRepPrimAPI_MakeBox(2.0, 3.0, 4.0).Shape(), BRepPrimAPI_MakeCylinder(1.0, 2.0).Shape()}) {
    const Model model = model_from_shape(shape);
    const UniformSize h(0.3);
    const SurfaceMesh whole = mesh_surface(model, h);
    REQUIRE(whole.failures.empty());
    const SurfaceMesh partial = mesh_surface(FaultyFace(model, 2), h);
    REQUIRE(partial.failures.size() == 1);
    CHECK(partial.failures[0].face == 2);
    CHECK(partial.failures[0].reason.find("surface evaluation failed") != std::string::npos);
    std::vector<std::array<Vec3, 3>> a, b;
    for (size_t t = 0; t < whole.tris.size(); ++t)
      if (whole.tri_face[t] != 2) a.push_back({whole.xyz[whole.tris[t][0]], whole.xyz[whole.tris[t][1]], whole.xyz[whole.tris[t][2]]});
    for (size_t t = 0; t < partial.tris.size(); ++t)
      b.push_back({partial.xyz[partial.tris[t][0]], partial.xyz[partial.tris[t][1]], partial.xyz[partial.tris[t][2]]});
    CHECK(a == b);
  }
}

TEST_CASE("a size map with a hole still gives a valid closed mesh", "[mesher]") {
  const Model box = model_from_shape(BRepPrimAPI_MakeBox(1.0, 1.0, 1.0).Shape());
  const SizeWithHole h(box, 0.1);
  const SurfaceMesh m = mesh_surface(box, h);
  const UniformSize h_ref(0.1);
  const MeshQuality q = mesh_quality(m, box, h_ref);
  require_valid_closed(box, m, q, std::sqrt(3.0));
}

namespace {

// One rectangular face [0, L] x [0, W] (z = 0) with a strongly distorted
// parametrisation, built analytically: S(u, v) = (x(u), y(v), 0) with
// x(u) = L (0.05 u + 0.95 u^3) and y(v) = W (0.1 v + 0.9 v^2).
// Points 1..4 at the corners, curves 1..4 the sides (t in [0, 1]).
class DistortedRectangle final : public Geometry {
 public:
  // stalls: x(u) = L (2u - u^2), whose speed falls to zero at u = 1 (a
  // trailing edge or tip closed by coincident control points), and the face
  // sheared by y += shear x (u-lines running obliquely into that edge).
  DistortedRectangle(double L, double W, bool stalls = false, double shear = 0)
      : L_(L), W_(W), stalls_(stalls), shear_(shear) {}
  int num_faces() const override { return 1; }
  int num_curves() const override { return 4; }
  int num_points() const override { return 4; }
  SurfaceD1 eval_face(int, const Vec2& uv) const override {
    return {Vec3(x(uv.x()), y(uv.y()) + shear_ * x(uv.x()), 0), Vec3(dx(uv.x()), shear_ * dx(uv.x()), 0),
            Vec3(0, dy(uv.y()), 0)};
  }
  bool principal_curvatures(int, const Vec2&, double& k1, double& k2) const override {
    k1 = k2 = 0;
    return true;
  }
  bool face_reversed(int) const override { return false; }
  UVBox face_uv_bounds(int) const override { return {Vec2(0, 0), Vec2(1, 1)}; }
  double face_period_u(int) const override { return 0; }
  double face_period_v(int) const override { return 0; }
  double face_area(int) const override { return L_ * W_; }
  double face_boundary_length(int) const override { return 2 * (L_ * std::hypot(1.0, shear_) + W_); }
  std::vector<FaceLoop> face_loops(int) const override {
    return {{{1, false, 0}, {2, false, 0}, {3, false, 0}, {4, false, 0}}};
  }
  bool project_to_face(int, const Vec3& p, Vec2& uv) const override {
    for (int it = 0; it < 50; ++it) {
      uv.x() = std::clamp(uv.x() - (x(uv.x()) - p.x()) / std::max(dx(uv.x()), 1e-3 * L_), 0.0, 1.0);
      uv.y() -= (y(uv.y()) + shear_ * x(uv.x()) - p.y()) / dy(uv.y());
    }
    return true;
  }
  void curve_range(int, double& t0, double& t1) const override {
    t0 = 0;
    t1 = 1;
  }
  bool curve_degenerated(int) const override { return false; }
  Vec3 eval_curve(int c, double t) const override { return eval_face(1, pcurve(c, t)).p; }
  Vec3 curve_tangent(int c, double t) const override {
    const SurfaceD1 s = eval_face(1, pcurve(c, t));
    const Vec2 d = pcurve(c, 1) - pcurve(c, 0);
    return s.du * d.x() + s.dv * d.y();
  }
  bool curve_curvature(int, double, double& k) const override {
    k = 0;
    return true;
  }
  double curve_length(int c) const override { return (eval_curve(c, 1) - eval_curve(c, 0)).norm(); }
  int curve_start_point(int c) const override { return c; }
  int curve_end_point(int c) const override { return c % 4 + 1; }
  Vec2 eval_pcurve(int c, int, int, double t) const override { return pcurve(c, t); }
  Vec3 point_xyz(int p) const override { return eval_face(1, corner(p)).p; }

 private:
  static Vec2 corner(int p) {
    const Vec2 c[4] = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
    return c[p - 1];
  }
  static Vec2 pcurve(int c, double t) { return corner(c) + t * (corner(c % 4 + 1) - corner(c)); }
  double x(double u) const { return stalls_ ? L_ * (2 * u - u * u) : L_ * (0.05 * u + 0.95 * u * u * u); }
  double dx(double u) const { return stalls_ ? L_ * (2 - 2 * u) : L_ * (0.05 + 2.85 * u * u); }
  double y(double v) const { return W_ * (0.1 * v + 0.9 * v * v); }
  double dy(double v) const { return W_ * (0.1 + 1.8 * v); }
  double L_, W_;
  bool stalls_;
  double shear_;
};

}  // namespace

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

namespace {

// A hand-made mesh of face 1 on fs: nodes at the surface's uv, the first
// `boundary` of them on the boundary (their global ids 0, 1, ...) in one
// loop, the rest inside; and the given triangles.
FaceMesh hand_mesh(FaceSurface& fs, const std::vector<Vec2>& surface_uv, int boundary,
                   std::vector<std::array<int, 3>> tris) {
  FaceMesh fm;
  fm.face = 1;
  fm.loops.emplace_back();
  for (int k = 0; k < static_cast<int>(surface_uv.size()); ++k) {
    const Vec2 uv = fs.to_mesher(surface_uv[k]);
    fm.add_node(uv, fs.eval(uv), k < boundary ? k : -1);
    if (k < boundary) fm.loops[0].push_back(k);
  }
  fm.tris = std::move(tris);
  return fm;
}

}  // namespace

TEST_CASE("a node left far off a short boundary edge is moved until no thin triangle is left", "[mesher]") {
  // A 10 x 10 square with a boundary node halfway along its bottom side and
  // one inner node near the bottom right corner, fanned to the boundary:
  // three of the five triangles are under 12 degrees.
  const DistortedRectangle square(10.0, 10.0);
  const UniformSize h(5.0);
  FaceSurface fs(square, h, 1);
  FaceMesh fm = hand_mesh(fs, {{0, 0}, {0.5, 0}, {1, 0}, {1, 1}, {0, 1}, {0.95, 0.08}}, 5,
                          {{0, 1, 5}, {1, 2, 5}, {2, 3, 5}, {3, 4, 5}, {4, 0, 5}});
  const std::vector<Vec2> uv = fm.uv;
  auto thin = [&] {
    int n = 0;
    for (const auto& t : fm.tris) n += min_angle_deg(fm.s[t[0]].p, fm.s[t[1]].p, fm.s[t[2]].p) < 12;
    return n;
  };
  REQUIRE(thin() == 3);
  CHECK(rescue_thin_triangles(fm, fs) == 1);
  CHECK(thin() == 0);
  for (int k = 0; k < 5; ++k) CHECK(fm.uv[k] == uv[k]);  // the boundary stays
  for (const auto& t : fm.tris) CHECK(orient(fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]]) > 0);
  CHECK((fm.s[5].p - square.eval_face(1, fs.to_surface(fm.uv[5])).p).norm() <= 1e-12);
  CHECK(rescue_thin_triangles(fm, fs) == 0);  // nothing under 15 degrees is left to move
}

TEST_CASE("two inner nodes left too close together are merged, and the two slivers between them go", "[mesher]") {
  // A 10 x 10 square fanned around two inner nodes 0.2 apart at its centre:
  // the triangles on the short side between them are under 3 degrees. Once
  // merged, the four triangles left are right-angled isosceles, give or take.
  const DistortedRectangle square(10.0, 10.0);
  const UniformSize h(5.0);
  FaceSurface fs(square, h, 1);
  std::vector<Vec2> at;  // the surface's uv of the corners and the two inner nodes
  for (const Vec3& p : {Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(10, 10, 0), Vec3(0, 10, 0), Vec3(5, 5, 0), Vec3(5.2, 5, 0)}) {
    at.emplace_back(0.5, 0.5);
    REQUIRE(square.project_to_face(1, p, at.back()));
  }
  FaceMesh fm = hand_mesh(fs, at, 4, {{0, 1, 5}, {1, 2, 5}, {2, 3, 4}, {3, 0, 4}, {0, 5, 4}, {2, 4, 5}});
  const std::vector<Vec2> uv = fm.uv;
  auto smallest = [&] {
    double a = 180;
    for (const auto& t : fm.tris) a = std::min(a, min_angle_deg(fm.s[t[0]].p, fm.s[t[1]].p, fm.s[t[2]].p));
    return a;
  };
  for (const auto& t : fm.tris) REQUIRE(orient(fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]]) > 0);
  REQUIRE(smallest() < 3);
  CHECK(collapse_thin_triangles(fm, fs) == 1);
  CHECK(fm.num_nodes() == 5);
  CHECK(fm.tris.size() == 4);
  CHECK(smallest() > 40);
  for (int k = 0; k < 4; ++k) CHECK(fm.uv[k] == uv[k]);  // the boundary stays, numbered as before
  CHECK(fm.loops == std::vector<std::vector<int>>{{0, 1, 2, 3}});
  for (const auto& t : fm.tris) {
    CHECK(orient(fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]]) > 0);
    for (int v : t) CHECK((v >= 0 && v < fm.num_nodes()));
  }
  CHECK(collapse_thin_triangles(fm, fs) == 0);
}

TEST_CASE("with a deviation bound the mesh stays that close to doubly curved, saddle and singly curved surfaces", "[mesher]") {
  // A sphere, a torus (convex outside, saddle-shaped inside) and a cylinder,
  // meshed from the curvature alone with a deviation bound d. The furthest
  // point of a triangle off the surface is its centre on the sphere and the
  // middles of its sides on the cylinder: both are measured, by their exact
  // distance to the surface.
  const double R = 50, r = 20, H = 100;
  struct Case {
    const char* name;
    TopoDS_Shape shape;
    std::function<double(const Vec3&)> distance;
  };
  const Case cases[] = {
      {"sphere", BRepPrimAPI_MakeSphere(R).Shape(), [&](const Vec3& x) { return std::abs(x.norm() - R); }},
      {"torus", BRepPrimAPI_MakeTorus(R, r).Shape(),
       [&](const Vec3& x) { return std::abs(std::hypot(std::hypot(x.x(), x.y()) - R, x.z()) - r); }},
      // Points of the mesh lie inside the (convex) solid: the nearest of its side and caps.
      {"cylinder", BRepPrimAPI_MakeCylinder(R, H).Shape(), [&](const Vec3& x) {
         return std::min({std::abs(R - std::hypot(x.x(), x.y())), std::abs(x.z()), std::abs(H - x.z())});
       }}};
  const double d = 0.05;
  for (const Case& c : cases) {
    RunOptions o;
    o.verbose = false;
    o.sizing.phi_c_deg = 90;  // the deviation bound decides
    o.sizing.deviation = d;
    o.sizing.local_proximity = false;
    o.sizing.h_min = 1e-3;
    o.sizing.h_max = 1e3;
    const auto run = test::run_model(model_from_shape(c.shape), o);
    const SurfaceMesh& m = run->mesh;
    REQUIRE(m.failures.empty());
    double worst = 0;
    int beyond = 0;  // triangles with a point further than d (and 2%)
    for (const auto& tr : m.tris) {
      double t_worst = c.distance((m.xyz[tr[0]] + m.xyz[tr[1]] + m.xyz[tr[2]]) / 3.0);
      for (int k = 0; k < 3; ++k)
        t_worst = std::max(t_worst, c.distance((m.xyz[tr[k]] + m.xyz[tr[(k + 1) % 3]]) / 2.0));
      worst = std::max(worst, t_worst);
      beyond += t_worst > 1.02 * d;
    }
    INFO(c.name << ": " << m.tris.size() << " triangles, furthest point " << worst / d << " d off the surface, "
                << beyond << " triangles beyond 1.02 d");
    // Edges are split while they lie further than d, unless a split would
    // leave a thin triangle (a few, next to the sphere's poles).
    CHECK(beyond <= 0.001 * m.tris.size());
    CHECK(worst <= 1.3 * d);
    CHECK(worst >= 0.5 * d);  // and not far finer than asked
  }
}

TEST_CASE("a pair of triangles on the same nodes facing apart is dropped, and every other triangle stays") {
  // A closed tetrahedron with a fin on its edge 0-1: the fin's two sides are
  // one triangle each on nodes 0, 1, 4, facing apart (two faces back to back,
  // no thickness). Edge 0-1 is used four times until the pair goes.
  SurfaceMesh m;
  m.xyz = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0.5, -1, 0)};
  m.tris = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {0, 1, 4}, {1, 0, 4}};
  m.tri_face = {1, 1, 1, 1, 2, 3};
  m.tri_uv.assign(m.tris.size(), {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)});
  drop_back_to_back(m);
  CHECK(m.stats.back_to_back_dropped == 2);
  REQUIRE(m.tris.size() == 4);
  REQUIRE(m.tri_face.size() == 4);
  REQUIRE(m.tri_uv.size() == 4);
  for (int f : m.tri_face) CHECK(f == 1);
  CHECK(m.xyz.size() == 5);  // node ids unchanged
  // The same triangle twice in one orientation is no fin: both stay.
  m.tris.push_back(m.tris[0]);
  m.tri_face.push_back(1);
  m.tri_uv.push_back(m.tri_uv[0]);
  drop_back_to_back(m);
  CHECK(m.stats.back_to_back_dropped == 0);
  CHECK(m.tris.size() == 5);
}

TEST_CASE("an inner edge two faces both mesh between the same curve nodes is flipped in one of them") {
  // Faces 1 and 2 meet along the curves through a = 0 and b = 1 (a thin
  // strut's sides near its tip): face 1 meshes the quad a, d, b, c with the
  // diagonal a-b, and so does face 2 with the quad a, e, b, f just above it.
  // Edge a-b is used four times until face 1 takes the diagonal c-d.
  SurfaceMesh m;
  m.xyz = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1, 0), Vec3(0.5, -1, 0), Vec3(0.5, 1, 0.1), Vec3(0.5, -1, 0.1)};
  m.tris = {{0, 1, 2}, {1, 0, 3}, {1, 0, 4}, {0, 1, 5}};
  m.tri_face = {1, 1, 2, 2};
  for (const auto& t : m.tris) m.tri_uv.push_back({m.xyz[t[0]].head<2>(), m.xyz[t[1]].head<2>(), m.xyz[t[2]].head<2>()});
  flip_shared_inner_edges(m);
  CHECK(m.stats.shared_edges_flipped == 1);
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : m.tris)
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
  CHECK(uses[{0, 1}] == 2);
  CHECK(uses[{2, 3}] == 2);
  // Face 1's triangles keep their side (normal +z) and their uv follow their nodes.
  for (size_t t = 0; t < 2; ++t) {
    const auto& n = m.tris[t];
    CHECK((m.xyz[n[1]] - m.xyz[n[0]]).cross(m.xyz[n[2]] - m.xyz[n[0]]).z() > 0);
    for (int k = 0; k < 3; ++k) CHECK((m.tri_uv[t][k] - m.xyz[n[k]].head<2>()).norm() == 0);
  }
  CHECK(m.tri_face[0] == 1);
  CHECK(m.tri_face[1] == 1);
}
