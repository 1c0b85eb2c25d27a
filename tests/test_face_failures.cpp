// Faults in meshing: a failed face is reported and the rest kept exactly, a bug ends the run, a holed size map closes.
#include <catch2/catch.hpp>

#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "cad/occt_model.h"
#include "core/geometry.h"
#include "core/size_field.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "tests/mesher_checks.h"

using namespace sizemesh;
using test::require_valid_closed;

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
