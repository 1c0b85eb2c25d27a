// The mesh keeps close to the CAD: area, sizes and angles at a resolving size, a deviation bound on curved faces.
#include <catch2/catch.hpp>

#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>

#include <algorithm>
#include <cmath>
#include <functional>

#include "cad/occt_model.h"
#include "core/size_field.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "tests/mesher_checks.h"
#include "tests/stage_runs.h"
#include "tests/test_models.h"

using namespace sizemesh;
using test::cad_area;

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
