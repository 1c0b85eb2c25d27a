// The mesh-level union: components the B-rep union does not take are cut
// with the rest as meshes. The result is one closed surface of the analytic
// area whose junction nodes lie on both CAD surfaces, with no sliver.
// CGAL first: OpenCASCADE defines a macro Handle that CGAL uses as a name.
#include "tests/exact_intersections.h"

#include <BRepCheck_Analyzer.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "app/pipeline.h"
#include "tests/brep_file.h"
#include "tests/temp_dir.h"

using namespace sizemesh;

namespace {

using test::write_compound;

std::unique_ptr<RunResult> mesh_file(const std::string& path, const LoadOptions& load, double h_max = 0,
                                     double h_min = 0) {
  RunOptions o;
  o.input = path;
  o.verbose = false;
  o.load = load;
  if (h_max > 0) o.sizing.h_max = h_max;
  if (h_min > 0) o.sizing.h_min = h_min;
  auto r = size_model(o, [](const std::string&) {});
  mesh_model(*r, o, [](const std::string&) {});
  return r;
}

double area(const SurfaceMesh& m) {
  double a = 0;
  for (const auto& t : m.tris) a += 0.5 * (m.xyz[t[1]] - m.xyz[t[0]]).cross(m.xyz[t[2]] - m.xyz[t[0]]).norm();
  return a;
}

// Every edge used twice, once each way: closed and consistently oriented.
void require_closed(const SurfaceMesh& m) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : m.tris)
    for (int k = 0; k < 3; ++k) ++uses[{t[k], t[(k + 1) % 3]}];
  int open = 0, bad = 0;
  for (const auto& [e, n] : uses) {
    const auto back = uses.find({e.second, e.first});
    open += back == uses.end();
    bad += n != 1;
  }
  CHECK(open == 0);
  CHECK(bad == 0);
}

long long cgal_pairs(const SurfaceMesh& m) {
  std::vector<std::array<double, 3>> xyz;
  for (const Vec3& x : m.xyz) xyz.push_back({x.x(), x.y(), x.z()});
  return test::exact_self_intersections(xyz, m.tris);
}

// The union's mesh: closed and consistently oriented, no crossing pair
// (CGAL's exact count), nothing inverted, no avoidable triangle under 12
// degrees.
void require_clean(const RunResult& r) {
  require_closed(r.mesh);
  CHECK(cgal_pairs(r.mesh) == 0);
  CHECK(r.report.quality.inverted == 0);
  CHECK(r.report.quality.avoidable_below_12 == 0);
}

// ... and the analytic area within 0.5%.
void require_clean(const RunResult& r, double expected_area) {
  CHECK(area(r.mesh) == Approx(expected_area).epsilon(0.005));
  require_clean(r);
}

}  // namespace

TEST_CASE("two crossing boxes united at mesh level: the analytic area, closed, junction nodes on both planes") {
  const test::TempDir dir("mesh_union_boxes");
  // A = [0,2]x[0,1]x[0,1]; B = [0.5,1.5]x[-0.5,1.5]x[0.25,0.75] pierces A along y.
  const TopoDS_Shape a = BRepPrimAPI_MakeBox(2.0, 1.0, 1.0).Shape();
  const TopoDS_Shape b = BRepPrimAPI_MakeBox(gp_Pnt(0.5, -0.5, 0.25), 1.0, 2.0, 0.5).Shape();
  LoadOptions load;
  load.mesh_union_all = true;
  const auto r = mesh_file(write_compound({a, b}, dir / "boxes.brep"), load);
  const Preparation& p = r->model->info().preparation;
  REQUIRE(p.components.size() == 2);
  CHECK(p.components[0].route == "mesh-level union");
  CHECK(p.components[1].route == "mesh-level union");
  CHECK(p.not_united.empty());
  CHECK(p.united_at_mesh_level == 2);
  CHECK(r->exit_code() == kOk);
  // A's 10 and B's 7, less A's 1 inside B and B's 3 inside A.
  require_clean(*r, 13.0);
  // The junction: four loops on A's planes y = 0 and y = 1, on B's sides.
  const double diag = std::sqrt(2.0 * 2.0 + 2.0 * 2.0 + 1.0);
  const MeshUnionResult& u = r->report.mesh_union;
  CHECK(u.united == 2);  // A the start, B cut into it
  CHECK(u.junction_nodes >= 8);
  CHECK(u.max_junction_gap <= 1e-7 * diag);
  CHECK(u.junction_nodes_off == 0);
  int on_junction = 0;
  for (const Vec3& x : r->mesh.xyz) {
    const bool on_a_plane = std::abs(x.y()) < 1e-7 * diag || std::abs(x.y() - 1) < 1e-7 * diag;
    const bool on_b_side = std::abs(x.x() - 0.5) < 1e-7 * diag || std::abs(x.x() - 1.5) < 1e-7 * diag ||
                           std::abs(x.z() - 0.25) < 1e-7 * diag || std::abs(x.z() - 0.75) < 1e-7 * diag;
    const bool in_b_box = x.x() > 0.5 - 1e-9 && x.x() < 1.5 + 1e-9 && x.z() > 0.25 - 1e-9 && x.z() < 0.75 + 1e-9;
    on_junction += on_a_plane && on_b_side && in_b_box;
  }
  CHECK(on_junction >= u.junction_nodes);
}

TEST_CASE("two boxes touching in a plane united at mesh level: every triangle keeps a face of the model") {
  // Where two meshes lie on one plane the corefinement cuts triangles by
  // plain Euler operations, outside its visitor; every triangle kept still
  // carries a face of the model (Pegasus's coincident root caps make the
  // case that leaves such pieces in the result: tests/test_union.cpp).
  const test::TempDir dir("mesh_union_touching");
  // A = [0,1]^3; B = [1,2]x[0.25,0.75]x[0.25,0.75] stands on A's face x = 1.
  const TopoDS_Shape a = BRepPrimAPI_MakeBox(1.0, 1.0, 1.0).Shape();
  const TopoDS_Shape b = BRepPrimAPI_MakeBox(gp_Pnt(1.0, 0.25, 0.25), 1.0, 0.5, 0.5).Shape();
  LoadOptions load;
  load.mesh_union_all = true;
  const auto r = mesh_file(write_compound({a, b}, dir / "touching.brep"), load, 0.1);
  const Preparation& p = r->model->info().preparation;
  REQUIRE(p.components.size() == 2);
  CHECK(p.not_united.empty());
  CHECK(r->exit_code() == kOk);
  const int faces = r->model->num_faces();
  int without = 0;
  for (int f : r->mesh.tri_face) without += f < 1 || f > faces;
  CHECK(without == 0);
  // A's 6 and B's 2.5, less the square 0.5 x 0.5 on each.
  require_clean(*r, 8.0);
}

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

TEST_CASE("a component of two closed shells that cross each other is united piece by piece") {
  // B = [0,1]x[0,3]x[1,2] and C = [0.25,0.75]x[1,2]x[0,3] cross; taken as one
  // part (as a repaired component whose halves close on their own, such as
  // a T-tail's through its fin), its mesh crosses itself. Each closed piece
  // joins on its own, so the part unites; A = [5,6]x[0,1]x[0,1] is the rest.
  const test::TempDir dir("mesh_union_pieces");
  const TopoDS_Shape a = BRepPrimAPI_MakeBox(gp_Pnt(5, 0, 0), 1.0, 1.0, 1.0).Shape();
  const TopoDS_Shape b = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 1), 1.0, 3.0, 1.0).Shape();
  const TopoDS_Shape c = BRepPrimAPI_MakeBox(gp_Pnt(0.25, 1, 0), 0.5, 1.0, 3.0).Shape();
  LoadOptions load;
  load.unite = false;
  auto r = mesh_file(write_compound({a, b, c}, dir / "pieces.brep"), load, 0.1);
  // The faces of B and C, by where their triangles lie.
  std::set<int> faces_bc;
  for (size_t t = 0; t < r->mesh.tris.size(); ++t)
    if (r->mesh.xyz[r->mesh.tris[t][0]].x() < 4) faces_bc.insert(r->mesh.tri_face[t]);
  REQUIRE(faces_bc.size() == 12);
  const MeshUnionResult u =
      unite_meshes(r->mesh, *r->model, *r->query, {std::vector<int>(faces_bc.begin(), faces_bc.end())});
  REQUIRE(u.failures.size() == 1);
  CHECK(u.failures[0].empty());
  CHECK(u.united == 1);
  require_closed(r->mesh);
  CHECK(cgal_pairs(r->mesh) == 0);
  // A's 6, B's 14 and C's 10, less B's 1 inside C and C's 3 inside B.
  CHECK(area(r->mesh) == Approx(26.0).epsilon(0.005));
}

TEST_CASE("a solid read with a face turned inside out is mended before the union: nothing outside it is lost") {
  // A = [0,2]x[0,1]x[0,1]; B = [1.5,2.5]x[0.25,0.75]x[0.25,0.75] crosses
  // its x = 2 end; C = [-0.5,0.5]x[0.25,0.75]x[0.25,0.75] crosses its x = 0
  // end, with one face turned inside out: its shell is badly oriented. Fused
  // as read, C was taken for a hollow and its part outside A was lost (the
  // mesh's area 11, exit 0). ShapeFix_Solid turns the face back first.
  const test::TempDir dir("mesh_union_invalid");
  const TopoDS_Shape a = BRepPrimAPI_MakeBox(2.0, 1.0, 1.0).Shape();
  const TopoDS_Shape b = BRepPrimAPI_MakeBox(gp_Pnt(1.5, 0.25, 0.25), 1.0, 0.5, 0.5).Shape();
  const TopoDS_Shape good_c = BRepPrimAPI_MakeBox(gp_Pnt(-0.5, 0.25, 0.25), 1.0, 0.5, 0.5).Shape();
  TopoDS_Shell shell;
  BRep_Builder builder;
  builder.MakeShell(shell);
  bool turned = false;
  for (TopExp_Explorer ex(good_c, TopAbs_FACE); ex.More(); ex.Next()) {
    builder.Add(shell, turned ? ex.Current() : ex.Current().Reversed());
    turned = true;
  }
  TopoDS_Solid c;
  builder.MakeSolid(c);
  builder.Add(c, shell);
  REQUIRE_FALSE(BRepCheck_Analyzer(c).IsValid());
  const auto r = mesh_file(write_compound({a, b, c}, dir / "boxes.brep"), LoadOptions{});
  const Preparation& p = r->model->info().preparation;
  REQUIRE(p.components.size() == 3);
  CHECK(p.not_united.empty());
  CHECK(p.united_at_mesh_level == 0);
  for (const auto& comp : p.components)
    CHECK((comp.route == "B-rep union" || comp.route == "the base others join"));
  CHECK(r->exit_code() == kOk);
  // A's area 10; each end cube adds its 5 faces of 0.25 and hides 0.25 of A.
  require_clean(*r, 10.0 + 2 * (5 * 0.25 - 0.25));
}

TEST_CASE("a box resting on another across a slot thinner than the mesh is united with it, the slot closed") {
  // B's floor lies 0.004 above A's top, a fifth of h_min = 0.02: the size
  // map cannot resolve the slot, and every triangle across it or along a
  // grazing cut would be a sliver. The side that resolves the slot moves
  // into the other; B's sides then meet A's top.
  const test::TempDir dir("mesh_union_slot");
  const double slot = 0.004;
  const TopoDS_Shape a = BRepPrimAPI_MakeBox(2.0, 2.0, 1.0).Shape();
  const TopoDS_Shape b = BRepPrimAPI_MakeBox(gp_Pnt(0.5, 0.5, 1.0 + slot), 1.0, 1.0, 0.5).Shape();
  LoadOptions load;
  load.mesh_union_all = true;
  const auto r = mesh_file(write_compound({a, b}, dir / "slot.brep"), load, 0.1, 0.02);
  const Preparation& p = r->model->info().preparation;
  REQUIRE(p.components.size() == 2);
  CHECK(p.not_united.empty());
  CHECK(r->exit_code() == kOk);
  CHECK(r->report.mesh_union.united == 2);
  CHECK(r->report.mesh_union.gap_nodes_closed > 0);
  // A's 16 less B's footprint, B's top and its sides down to A's top; the
  // slot left open would add B's floor and A's top under it (19.98).
  require_clean(*r, 18.0);
  // One surface: every triangle reached from the first across its edges.
  std::map<std::pair<int, int>, std::vector<int>> edge_tris;
  for (size_t t = 0; t < r->mesh.tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int u = r->mesh.tris[t][k], v = r->mesh.tris[t][(k + 1) % 3];
      edge_tris[{std::min(u, v), std::max(u, v)}].push_back(static_cast<int>(t));
    }
  std::vector<char> seen(r->mesh.tris.size(), 0);
  std::vector<int> stack{0};
  seen[0] = 1;
  size_t reached = 1;
  while (!stack.empty()) {
    const int t = stack.back();
    stack.pop_back();
    for (int k = 0; k < 3; ++k) {
      const int u = r->mesh.tris[t][k], v = r->mesh.tris[t][(k + 1) % 3];
      for (int n : edge_tris[{std::min(u, v), std::max(u, v)}])
        if (!seen[n]) seen[n] = 1, ++reached, stack.push_back(n);
    }
  }
  CHECK(reached == r->mesh.tris.size());
}
