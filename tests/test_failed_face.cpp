// A face that cannot be meshed is reported by id with a reason; every other
// face is still meshed and nothing computed is lost.
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>

#include <catch2/catch.hpp>
#include <set>

#include "geometry/occt_model.h"
#include "mesher/mesh_surface.h"
#include "sizing/size_function.h"

using namespace sizemesh;

namespace {

// The model, except that one face's surface cannot be evaluated.
class BrokenFace final : public Geometry {
 public:
  BrokenFace(const Geometry& g, int broken) : g_(g), broken_(broken) {}
  int num_faces() const override { return g_.num_faces(); }
  int num_curves() const override { return g_.num_curves(); }
  int num_points() const override { return g_.num_points(); }
  SurfaceD1 eval_face(int f, const Vec2& uv) const override {
    if (f == broken_) throw Error("surface evaluation failed");
    return g_.eval_face(f, uv);
  }
  bool max_curvature(int f, const Vec2& uv, double& k) const override { return g_.max_curvature(f, uv, k); }
  bool face_reversed(int f) const override { return g_.face_reversed(f); }
  UVBox face_uv_bounds(int f) const override { return g_.face_uv_bounds(f); }
  double face_period_u(int f) const override { return g_.face_period_u(f); }
  double face_period_v(int f) const override { return g_.face_period_v(f); }
  double face_area(int f) const override { return g_.face_area(f); }
  double face_boundary_length(int f) const override { return g_.face_boundary_length(f); }
  std::vector<FaceLoop> face_loops(int f) const override { return g_.face_loops(f); }
  bool project_to_face(int f, const Vec3& xyz, Vec2& uv) const override { return g_.project_to_face(f, xyz, uv); }
  void curve_range(int c, double& t0, double& t1) const override { g_.curve_range(c, t0, t1); }
  bool curve_degenerated(int c) const override { return g_.curve_degenerated(c); }
  Vec3 eval_curve(int c, double t) const override { return g_.eval_curve(c, t); }
  Vec3 curve_tangent(int c, double t) const override { return g_.curve_tangent(c, t); }
  bool curve_curvature(int c, double t, double& k) const override { return g_.curve_curvature(c, t, k); }
  double curve_length(int c) const override { return g_.curve_length(c); }
  int curve_start_point(int c) const override { return g_.curve_start_point(c); }
  int curve_end_point(int c) const override { return g_.curve_end_point(c); }
  Vec2 eval_pcurve(int c, int f, int side, double t) const override { return g_.eval_pcurve(c, f, side, t); }
  Vec3 point_xyz(int p) const override { return g_.point_xyz(p); }

 private:
  const Geometry& g_;
  int broken_;
};

}  // namespace

TEST_CASE("a face that cannot be meshed is reported by id and reason, the others are kept") {
  for (const TopoDS_Shape& shape : {BRepPrimAPI_MakeBox(2.0, 3.0, 4.0).Shape(), BRepPrimAPI_MakeCylinder(1.0, 2.0).Shape()}) {
    Model model = model_from_shape(shape);
    const SurfaceMesh whole = mesh_surface(model, UniformSize(0.3));
    REQUIRE(whole.failures.empty());
    const int broken = 2;
    const SurfaceMesh partial = mesh_surface(BrokenFace(model, broken), UniformSize(0.3));
    REQUIRE(partial.failures.size() == 1);
    CHECK(partial.failures[0].face == broken);
    CHECK(partial.failures[0].reason.find("surface evaluation failed") != std::string::npos);
    std::set<int> meshed;
    size_t whole_others = 0, partial_others = 0;
    for (int f : whole.tri_face) whole_others += f != broken;
    for (int f : partial.tri_face) {
      meshed.insert(f);
      partial_others += f != broken;
    }
    CHECK(meshed.count(broken) == 0);
    CHECK(static_cast<int>(meshed.size()) == model.num_faces() - 1);
    CHECK(partial_others == whole_others);  // the other faces are meshed exactly as before
  }
}
