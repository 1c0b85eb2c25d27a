// A file meshed through the pipeline and the checks of a clean union of meshes, for the mesh-level union's tests.
#pragma once

// CGAL first: OpenCASCADE defines a macro Handle that CGAL uses as a name.
#include "tests/exact_intersections.h"

#include <catch2/catch.hpp>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/pipeline.h"

namespace sizemesh::test {

// The file at path sized and meshed by the pipeline, with these load options and size bounds.
inline std::unique_ptr<RunResult> mesh_file(const std::string& path, const LoadOptions& load, double h_max = 0,
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

inline double area(const SurfaceMesh& m) {
  double a = 0;
  for (const auto& t : m.tris) a += 0.5 * (m.xyz[t[1]] - m.xyz[t[0]]).cross(m.xyz[t[2]] - m.xyz[t[0]]).norm();
  return a;
}

// Every edge used twice, once each way: closed and consistently oriented.
inline void require_closed(const SurfaceMesh& m) {
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

inline long long cgal_pairs(const SurfaceMesh& m) {
  std::vector<std::array<double, 3>> xyz;
  for (const Vec3& x : m.xyz) xyz.push_back({x.x(), x.y(), x.z()});
  return test::exact_self_intersections(xyz, m.tris);
}

// The union's mesh: closed and consistently oriented, no crossing pair
// (CGAL's exact count), nothing inverted, no avoidable triangle under 12
// degrees.
inline void require_clean(const RunResult& r) {
  require_closed(r.mesh);
  CHECK(cgal_pairs(r.mesh) == 0);
  CHECK(r.report.quality.inverted == 0);
  CHECK(r.report.quality.avoidable_below_12 == 0);
}

// ... and the analytic area within 0.5%.
inline void require_clean(const RunResult& r, double expected_area) {
  CHECK(area(r.mesh) == Approx(expected_area).epsilon(0.005));
  require_clean(r);
}

}  // namespace sizemesh::test
