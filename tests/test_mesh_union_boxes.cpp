// The union of meshes of boxes (crossing, touching, self-crossing, turned inside out, over a slot) is clean and exact.
// CGAL first (tests/mesh_union_checks.h): OpenCASCADE defines a macro Handle that CGAL uses as a name.
#include "tests/mesh_union_checks.h"

#include <BRepCheck_Analyzer.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRep_Builder.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "app/pipeline.h"
#include "tests/brep_file.h"
#include "tests/temp_dir.h"

using namespace sizemesh;
using test::area;
using test::cgal_pairs;
using test::mesh_file;
using test::require_clean;
using test::require_closed;
using test::write_compound;

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
  // case that leaves such pieces in the result: tests/test_union_aircraft.cpp).
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
