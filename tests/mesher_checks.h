// A graded size map, the CAD's area and the checks of a valid closed mesh, shared by the surface mesher's tests.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "core/geometry.h"
#include "core/size_field.h"
#include "mesher/quality.h"
#include "mesher/surface_mesh.h"
#include "tests/test_models.h"

namespace sizemesh::test {

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

inline double cad_area(const Geometry& g) {
  double a = 0;
  for (int f = 1; f <= g.num_faces(); ++f) a += g.face_area(f);
  return a;
}

// How far x lies off face f's surface, x a point of a triangle of f at
// (about) uv there: the distance to the surface point at uv, or to the
// nearest one Newton finds from it where that is nearer. A triangle of a
// composite face may have corners on a neighbouring face, whose uv on f is
// only the nearest point inside f.
inline double off_surface(const Geometry& g, int f, Vec2 uv, const Vec3& x) {
  const double at_uv = (g.eval_face(f, uv).p - x).norm();
  return g.project_to_face(f, x, uv) ? std::min(at_uv, (g.eval_face(f, uv).p - x).norm()) : at_uv;
}

// Every property the mesher promises for a closed solid.
inline void require_valid_closed(const Geometry& g, const SurfaceMesh& m, const MeshQuality& q, double diag,
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

}  // namespace sizemesh::test
