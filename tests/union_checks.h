// The check of a run's report that its mesh is one closed surface, shared by the union's tests.
#pragma once

#include <catch2/catch.hpp>

namespace sizemesh::test {

// The report's mesh: one closed, consistently oriented surface with nothing
// crossing and every face meshed.
template <class Json>
void check_one_closed_surface(const Json& m) {
  CHECK(m["boundary_edges"] == 0);
  CHECK(m["nonmanifold_edges"] == 0);
  CHECK(m["orientation_conflicts"] == 0);
  CHECK(m["self_intersecting_pairs"] == 0);
  CHECK(m["failed_faces"].empty());
}

}  // namespace sizemesh::test
