// Nothing outside the other components is lost: every point of the CAD
// faces as read (sewn, before repair and union) lies on the wetted surface,
// or inside the volume it bounds (buried in another component, or an
// internal plane the repair took out). A face dropped by mistake (a skin
// half taken out instead of the plane between the halves) leaves points
// that are neither.
// CGAL first: OpenCASCADE defines a macro Handle that CGAL uses as a name.
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "app/pipeline.h"
#include "tests/test_models.h"

using namespace sizemesh;

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

// What became of the sample points of the faces as read.
struct Coverage {
  int samples = 0;
  int on_surface = 0;  // within a tenth of the local element size of the mesh
  int buried = 0;      // inside the volume the mesh bounds
  int lost = 0;        // neither
};

// Points of face f on an n x n grid over its uv box, those inside its
// boundary loops (their pcurves as polygons, even-odd rule).
std::vector<Vec3> face_samples(const Geometry& g, int f, int n) {
  std::vector<std::vector<Vec2>> loops;
  for (const FaceLoop& loop : g.face_loops(f)) {
    std::vector<Vec2> poly;
    for (const CurveUse& use : loop) {
      double t0, t1;
      g.curve_range(use.curve, t0, t1);
      constexpr int kSteps = 64;
      for (int k = 0; k < kSteps; ++k) {
        const double s = k / double(kSteps);
        poly.push_back(g.eval_pcurve(use.curve, f, use.side, use.reversed ? t1 - s * (t1 - t0) : t0 + s * (t1 - t0)));
      }
    }
    loops.push_back(std::move(poly));
  }
  const UVBox box = g.face_uv_bounds(f);
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec2 uv = box.lo + Vec2((i + 0.5) / n, (j + 0.5) / n).cwiseProduct(box.hi - box.lo);
      bool in = false;
      for (const auto& poly : loops)
        for (size_t a = 0, b = poly.size() - 1; a < poly.size(); b = a++)
          if ((poly[a].y() > uv.y()) != (poly[b].y() > uv.y()) &&
              uv.x() < poly[b].x() + (poly[a].x() - poly[b].x()) * (uv.y() - poly[b].y()) / (poly[a].y() - poly[b].y()))
            in = !in;
      if (in) out.push_back(g.eval_face(f, uv).p);
    }
  return out;
}

// Samples: a uv grid on every face of `raw`. A sample is on the surface
// when its distance to the mesh is under half the longest side of the
// nearest triangle (a mesh sized by curvature at the default 15 degrees per
// element lies within h / 30 of the surface it follows).
Coverage coverage(const Geometry& raw, const SurfaceMesh& m) {
  Mesh mesh;
  std::vector<Mesh::Vertex_index> v;
  for (const Vec3& x : m.xyz) v.push_back(mesh.add_vertex(K::Point_3(x.x(), x.y(), x.z())));
  for (const auto& t : m.tris) mesh.add_face(v[t[0]], v[t[1]], v[t[2]]);
  REQUIRE(mesh.number_of_faces() == m.tris.size());
  Tree tree(faces(mesh).first, faces(mesh).second, mesh);
  tree.accelerate_distance_queries();
  const CGAL::Side_of_triangle_mesh<Mesh, K> inside(tree);
  Coverage c;
  for (int f = 1; f <= raw.num_faces(); ++f)
    for (const Vec3& x : face_samples(raw, f, 24)) {
      const K::Point_3 p(x.x(), x.y(), x.z());
      const auto [closest, face] = tree.closest_point_and_primitive(p);
      double longest = 0;
      for (auto h : CGAL::halfedges_around_face(mesh.halfedge(face), mesh))
        longest = std::max(longest, std::sqrt(CGAL::squared_distance(mesh.point(mesh.source(h)),
                                                                     mesh.point(mesh.target(h)))));
      ++c.samples;
      if (std::sqrt(CGAL::squared_distance(p, closest)) <= 0.5 * longest) ++c.on_surface;
      else if (inside(p) == CGAL::ON_BOUNDED_SIDE) ++c.buried;
      else ++c.lost;
    }
  return c;
}

}  // namespace

TEST_CASE("every point of the faces as read lies on the wetted surface or inside it", "[models]") {
  // The F-16 and the manta (components united as B-reps, internal caps and
  // planes taken out) and OpenVSP's two exports of a blunt-trailing-edge
  // wing (a planform plane between the halves of its skin).
  for (const char* file :
       {"f16_openvsp.stp", "manta2_openvsp.stp", "wing_blunt_te_openvsp.stp", "wing_blunt_te2_openvsp.stp"}) {
    SECTION(file) {
      RunOptions o;
      o.input = test::model_path(file);
      o.verbose = false;
      auto r = size_model(o, [](const std::string&) {});
      mesh_model(*r, o, [](const std::string&) {});
      REQUIRE(r->mesh.failures.empty());
      REQUIRE(r->model->info().preparation.not_united.empty());
      const Model raw = load_model(o.input, test::load_options(true, false));
      const Coverage c = coverage(raw, r->mesh);
      INFO(file << ": " << c.samples << " samples, " << c.on_surface << " on the surface, " << c.buried
                << " buried, " << c.lost << " lost");
      CHECK(c.samples > 1000);
      CHECK(c.lost == 0);
      CHECK(c.on_surface > c.samples / 2);
    }
  }
}
