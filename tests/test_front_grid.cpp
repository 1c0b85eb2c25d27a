// The front's search grid (mesher/edge_grid.h) on faces far longer in space
// one way than the other: cells about square in space, so each step looks
// at a bounded number of front edges (the work its budget counts), not
// at every edge of a strip listed in hundreds of cells.
#include <BRepPrimAPI_MakeBox.hxx>

#include <catch2/catch.hpp>

#include "cad/occt_model.h"
#include "mesher/edge_grid.h"
#include "tests/stage_runs.h"

using namespace sizemesh;

TEST_CASE("the edge grid's cells follow the box's aspect in space; near-square boxes keep the square grid") {
  // 10,000 edges on a box 100 times longer along u: cells 1.5 sqrt(n * 100)
  // by 1.5 sqrt(n / 100), each listing an edge along u once or twice.
  EdgeGrid grid;
  grid.init(Vec2(0, 0), Vec2(1, 1), 10000, 100.0);
  int listed = 0;
  // An edge of a hundredth of the box's space length along u (0.01 in u).
  grid.insert(0, Vec2(0.5, 0.5), Vec2(0.51, 0.5));
  grid.query(Vec2(0, 0), Vec2(1, 1), [](int) { return true; }, [&](int) { ++listed; });
  CHECK(listed <= 20);
  EdgeGrid square;
  square.init(Vec2(0, 0), Vec2(1, 1), 10000, 1.0);
  int listed_square = 0;
  square.insert(0, Vec2(0.5, 0.5), Vec2(0.51, 0.5));
  square.query(Vec2(0, 0), Vec2(1, 1), [](int) { return true; }, [&](int) { ++listed_square; });
  CHECK(listed_square == 2);  // 150 cells a side: 0.01 of u spans two
}

TEST_CASE("a box 230 times longer than wide meshes with bounded front work per step on its strip faces") {
  // 1000 x 4.4 x 4.4 at size 0.5: each long face a strip of 2000 x 9 elements.
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(1000.0, 4.4, 4.4).Shape();
  RunOptions o;
  o.verbose = false;
  o.sizing.h_max = 0.5;
  o.sizing.h_min = 0.1;
  const auto r = test::run_model(model_from_shape(box), o);
  REQUIRE(r->mesh.failures.empty());
  CHECK(r->report.quality.boundary_edges == 0);
  CHECK(r->mesh.tris.size() > 60000);
  const double per_step = double(r->mesh.stats.front_work) / r->mesh.stats.front_steps;
  INFO("front work per step " << per_step);
  CHECK(per_step < 150);
}
