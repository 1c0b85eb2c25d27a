// The surface mesher under the automatic size map (paper 3 + 4.1), on every
// shared model: no face fails; closed models are watertight and consistently
// oriented; no inverted or zero-area triangle; nodes on their surfaces; the
// CAD area within 0.5%; under 0.05% of triangles below 12 degrees and 0.5%
// below 24; 90% of edges of conforming length. (Thread independence: test_mesher.)
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "geometry/background_mesh.h"
#include "geometry/model.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "sizing/initial_sizes.h"
#include "sizing/size_query.h"
#include "sizing/smooth.h"
#include "tests/test_models.h"

using namespace sizemesh;

TEST_CASE("shared models under the automatic size map meet every mesh requirement", "[mesher][size_map]") {
  for (const auto& c : test::shared_models()) {
    SECTION(c.file) {
      const Model model = load_model(test::model_path(c.file));
      const double diag = model.info().diagonal();
      const BackgroundMesh bg = build_background_mesh(model);
      SizingParams params;
      params.h_min_rel = 1e-3;  // keeps the test short: at most about 1e6 triangles a model
      SizeMap map = initial_sizes(model, bg, params, diag);
      smooth(bg, map);
      std::vector<double> pu, pv;
      for (int f = 1; f <= model.num_faces(); ++f) {
        pu.push_back(model.face_period_u(f));
        pv.push_back(model.face_period_v(f));
      }
      const SizeQuery h(bg, map.h, pu, pv);
      const SurfaceMesh m = mesh_surface(model, h);
      const MeshQuality q = mesh_quality(m, model, h);
      double area = 0;
      for (int f = 1; f <= model.num_faces(); ++f) area += model.face_area(f);
      INFO(c.file << ": " << q.triangles << " triangles; below 12 deg " << q.below_12 << ", below 24 deg "
                  << q.below_24 << "; conformity " << q.size_conformity << "; area " << q.area << " vs CAD "
                  << area << (m.failures.empty() ? "" : "; failure: " + m.failures[0].reason));
      REQUIRE(m.failures.empty());
      if (c.closed) {
        CHECK(q.boundary_edges == 0);
        CHECK(q.nonmanifold_edges == 0);
      }
      CHECK(q.orientation_conflicts == 0);
      CHECK(q.inverted == 0);
      CHECK(q.zero_area == 0);
      CHECK(q.max_inner_node_distance <= 1e-9 * diag);
      CHECK(std::abs(q.area - area) <= 0.005 * area);
      CHECK(q.below_12 <= 0.0005 * q.triangles);
      CHECK(q.below_24 <= 0.005 * q.triangles);
      CHECK(q.size_conformity >= 0.90);
    }
  }
}
