// Sharp corners and narrow rounded edges: long first segments, one forced thin triangle, strips closed across.
#include <catch2/catch.hpp>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <ElCLib.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <gp.hxx>
#include <gp_Ax2.hxx>
#include <gp_Circ.hxx>

#include <cmath>
#include <set>
#include <vector>

#include "cad/occt_model.h"
#include "core/size_field.h"
#include "mesher/discretise_curves.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "tests/mesher_checks.h"

using namespace sizemesh;
using test::require_valid_closed;

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
