// Background patches of the faces whose curves OCCT's own edge discretisation
// throws on: OpenVSP fins split at their fold, whose root and tip curves end
// on a knot span standing still at the trailing edge (cad/tessellate.cpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "background/background_mesh.h"
#include "cad/model.h"
#include "tests/background_checks.h"
#include "tests/test_models.h"

using namespace sizemesh;

TEST_CASE("every face of the fins split at their fold has a background patch, closed with its neighbours") {
  const std::vector<std::pair<const char*, std::vector<int>>> models = {
      {"b777_nosplit_openvsp.stp", {1, 3, 4}}, {"tbw_sugar_openvsp.stp", {26, 28, 29}}};
  for (const auto& [file, fin] : models) {
    SECTION(file) {
      Model model = load_model(test::model_path(file));
      const BackgroundOptions opt;
      const BackgroundMesh bg = build_background_mesh(model, opt);
      CHECK(bg.faces_without_patch.empty());
      double cad_area = 0;
      for (int f = 1; f <= model.num_faces(); ++f) {
        INFO("face " << f);
        CHECK(!bg.patches[f - 1].tris.empty());
        cad_area += model.face_area(f);
      }
      CHECK(std::abs(bg.area() - cad_area) <= 0.01 * cad_area);
      CHECK(test::open_background_edges(model, bg) == 0);
      // The fin's nodes lie on their faces, each curve's nodes on both faces along it.
      double worst = 0;
      for (int f : fin) {
        const FacePatch& p = bg.patches[f - 1];
        for (size_t l = 0; l < p.uv.size(); ++l)
          worst = std::max(worst, (model.eval_face(f, p.uv[l]).p - bg.xyz[p.vertex[l]]).norm());
      }
      CHECK(worst <= 2 * opt.deflection_rel * model.info().diagonal());
    }
  }
}
