// Solids and shared models mesh watertight, valid, outward, on the CAD's area with good angles, whatever the threads.
#include <catch2/catch.hpp>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <gp_Ax2.hxx>

#include <cmath>
#include <vector>

#include "cad/occt_model.h"
#include "core/size_field.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "tests/mesher_checks.h"
#include "tests/test_models.h"

using namespace sizemesh;
using test::cad_area;
using test::GradedSize;
using test::require_valid_closed;

namespace {

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
