// The union of meshes on curved faces: junction nodes on both surfaces, faces meshed again from the junction's size.
// CGAL first (tests/mesh_union_checks.h): OpenCASCADE defines a macro Handle that CGAL uses as a name.
#include "tests/mesh_union_checks.h"

#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <gp_Ax2.hxx>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <vector>

#include "app/pipeline.h"
#include "tests/brep_file.h"
#include "tests/temp_dir.h"

using namespace sizemesh;
using test::mesh_file;
using test::require_clean;
using test::write_compound;

TEST_CASE("a cylinder through a box united at mesh level: junction nodes on the plane and on the cylinder") {
  const test::TempDir dir("mesh_union_cylinder");
  const double radius = 0.3;
  const TopoDS_Shape a = BRepPrimAPI_MakeBox(2.0, 1.0, 1.0).Shape();
  const TopoDS_Shape b =
      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(1.0, -0.5, 0.5), gp_Dir(0, 1, 0)), radius, 2.0).Shape();
  LoadOptions load;
  load.mesh_union = {2};
  const auto r = mesh_file(write_compound({a, b}, dir / "pipe.brep"), load, 0.1);
  const Preparation& p = r->model->info().preparation;
  REQUIRE(p.components.size() == 2);
  CHECK(p.not_united.empty());
  CHECK(r->exit_code() == kOk);
  // The box less two discs, the cylinder's outer unit length and its caps.
  const double expected = 10.0 + 2 * kPi * radius;
  require_clean(*r, expected);
  const double diag = std::sqrt(2.0 * 2.0 + 2.0 * 2.0 + 1.0);
  const MeshUnionResult& u = r->report.mesh_union;
  CHECK(u.united == 1);
  CHECK(u.max_junction_gap <= 1e-7 * diag);
  CHECK(u.junction_nodes_off == 0);
  // No node of the planes y = 0 or y = 1 inside the cylinder; the nodes
  // on its circle are the junction's: they lie on both surfaces.
  int junction = 0, inside = 0;
  for (const Vec3& x : r->mesh.xyz) {
    const double rho = std::hypot(x.x() - 1.0, x.z() - 0.5);
    const bool on_plane = std::abs(x.y()) < 1e-7 * diag || std::abs(x.y() - 1) < 1e-7 * diag;
    if (!on_plane) continue;
    inside += rho < radius - 1e-7 * diag;
    junction += std::abs(rho - radius) <= 1e-7 * diag;
  }
  CHECK(inside == 0);
  CHECK(junction == u.junction_nodes);
  CHECK(junction >= 2 * 2 * kPi * radius / 0.1);
  // The planes y = 0 and y = 1 and the cylinder's side (two regions, across
  // its seam) meshed again from the junction, sampled to the size: every
  // junction edge within a quarter of h = 0.1.
  CHECK(r->report.cut_faces.faces_remeshed == 3);
  CHECK(r->report.cut_faces.faces_kept == 0);
  // Each circle keeps its node on the cylinder's seam; the others are new.
  CHECK(r->report.cut_faces.junction_nodes == u.junction_nodes - 2);
  REQUIRE(u.junction.size() == static_cast<size_t>(u.junction_nodes));  // two closed circles
  for (const auto& [a, b] : u.junction) {
    const double length = (r->mesh.xyz[a] - r->mesh.xyz[b]).norm();
    CHECK(length > 0.075);
    CHECK(length < 0.125);
  }
}

TEST_CASE("a thin tube through a coarse box: the box is meshed from the junction's size, growing at the gradient bound") {
  // Each component's size map saw only itself: at the junction the tube's
  // curvature asks for elements some forty times smaller than the box's
  // plane. The junction is sampled to the finer, and the box's top is meshed
  // with sizes grown from it at ln(beta) per unit length (Eq. 12): no fan of
  // slivers from the junction's nodes to the plane's coarse ones.
  const test::TempDir dir("mesh_union_tube");
  const double radius = 0.1;
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(10.0, 10.0, 10.0).Shape();
  const TopoDS_Shape tube = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(5, 5, 5), gp_Dir(0, 0, 1)), radius, 7.0).Shape();
  LoadOptions load;
  load.mesh_union_all = true;
  const auto r = mesh_file(write_compound({box, tube}, dir / "tube.brep"), load);
  CHECK(r->model->info().preparation.not_united.empty());
  CHECK(r->exit_code() == kOk);
  // The box less the tube's foot, the tube's 2 above the box and its cap.
  require_clean(*r, 600.0 + 2 * kPi * radius * 2.0);
  CHECK(r->report.cut_faces.faces_kept == 0);
  // On the box's top (z = 10): the longest edge of the triangles at each
  // distance d from the tube's axis is within twice h_j + ln(1.2) d, h_j the
  // longest junction edge.
  const MeshUnionResult& u = r->report.mesh_union;
  REQUIRE(!u.junction.empty());
  double hj = 0;
  for (const auto& [a, b] : u.junction) hj = std::max(hj, (r->mesh.xyz[a] - r->mesh.xyz[b]).norm());
  INFO("junction edges up to " << hj);
  CHECK(hj < 0.25 * radius * 2 * kPi);
  int top = 0, over = 0;
  double worst = 0;
  for (const auto& t : r->mesh.tris) {
    bool on_top = true;
    for (int v : t) on_top = on_top && std::abs(r->mesh.xyz[v].z() - 10.0) < 1e-9;
    if (!on_top) continue;
    ++top;
    double d = HUGE_VAL, longest = 0;
    for (int k = 0; k < 3; ++k) {
      const Vec3& x = r->mesh.xyz[t[k]];
      d = std::min(d, std::hypot(x.x() - 5, x.y() - 5) - radius);
      longest = std::max(longest, (r->mesh.xyz[t[(k + 1) % 3]] - x).norm());
    }
    const double ratio = longest / (hj + std::log(1.2) * std::max(d, 0.0));
    worst = std::max(worst, ratio);
    over += ratio > 2;
  }
  INFO(top << " triangles on the top, worst ratio " << worst);
  CHECK(top > 0);
  CHECK(over == 0);
}

TEST_CASE("a thin tube through a coarse box's edge: the edge's segments at the junction take the junction's size") {
  // The tube crosses the box's vertical edge x = y = 10 at z = 5 -+ r: the
  // cut splits two of the edge's coarse segments there. The edge is spaced
  // again from the junction's size, growing away from it, and no segment
  // beside a junction corner is left long (a fan of slivers to the junction)
  // or a stub.
  const test::TempDir dir("mesh_union_edge");
  const double radius = 0.1, s = std::sqrt(0.5);
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(10.0, 10.0, 10.0).Shape();
  const TopoDS_Shape tube =
      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(10 - s, 10 + s, 5), gp_Dir(1, -1, 0)), radius, 2.0).Shape();
  LoadOptions load;
  load.mesh_union_all = true;
  const auto r = mesh_file(write_compound({box, tube}, dir / "edge.brep"), load);
  CHECK(r->model->info().preparation.not_united.empty());
  CHECK(r->exit_code() == kOk);
  require_clean(*r);
  const MeshUnionResult& u = r->report.mesh_union;
  REQUIRE(!u.junction.empty());
  double hj = 0;
  for (const auto& [a, b] : u.junction) hj = std::max(hj, (r->mesh.xyz[a] - r->mesh.xyz[b]).norm());
  // The edge's nodes outside the tube, by height: the two corners are the
  // last below z = 5 and the first above it, the junction between them.
  std::vector<double> z;
  for (size_t n = 0; n < r->mesh.xyz.size(); ++n) {
    const Vec3& x = r->mesh.xyz[n];
    if (std::abs(x.x() - 10) < 1e-9 && std::abs(x.y() - 10) < 1e-9) z.push_back(x.z());
  }
  std::sort(z.begin(), z.end());
  const auto above = std::upper_bound(z.begin(), z.end(), 5.0);
  REQUIRE(above != z.begin());
  REQUIRE(above + 1 < z.end());
  const double low = *(above - 1), high = *above;
  CHECK(low == Approx(5 - radius).margin(0.01 * radius));
  CHECK(high == Approx(5 + radius).margin(0.01 * radius));
  REQUIRE(above - 2 >= z.begin());
  const double below_segment = low - *(above - 2), above_segment = *(above + 1) - high;
  INFO("junction edges up to " << hj << ", edge segments beside the corners " << below_segment << ", " << above_segment);
  for (double seg : {below_segment, above_segment}) {
    CHECK(seg < 2 * hj);
    CHECK(seg > 0.25 * hj);
  }
}

TEST_CASE("a box through a sphere united at mesh level: the sphere, poles and seam, meshed again from the junction") {
  const test::TempDir dir("mesh_union_sphere");
  const TopoDS_Shape sphere = BRepPrimAPI_MakeSphere(1.0).Shape();
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(0.5, -0.3, -0.3), 1.5, 0.6, 0.6).Shape();
  LoadOptions load;
  load.mesh_union_all = true;
  const auto r = mesh_file(write_compound({sphere, box}, dir / "ball.brep"), load, 0.1);
  CHECK(r->model->info().preparation.not_united.empty());
  CHECK(r->exit_code() == kOk);
  require_clean(*r);
  // The sphere's one face (a seam, a pole at each end) and the box's four
  // sides it cuts: all meshed again, the junction sampled to the size.
  CHECK(r->report.cut_faces.faces_remeshed == 5);
  CHECK(r->report.cut_faces.faces_kept == 0);
  const MeshUnionResult& u = r->report.mesh_union;
  CHECK(u.junction_nodes_off == 0);
  for (const auto& [a, b] : u.junction) {
    const double length = (r->mesh.xyz[a] - r->mesh.xyz[b]).norm();
    CHECK(length > 0.05);
    CHECK(length < 0.15);
  }
}
