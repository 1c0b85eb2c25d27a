#include "io/background_output.h"

#include <algorithm>

#include "sizing/smooth.h"

namespace sizemesh {

void write_background(const std::string& path, const BackgroundMesh& bg, const std::vector<Field>& extra_point,
                      const std::vector<Field>& extra_cell) {
  std::vector<Field> point = {{"classification_dim", {}}, {"classification_id", {}}};
  for (int v = 0; v < bg.num_vertices(); ++v) {
    point[0].second.push_back(bg.dim[v]);
    point[1].second.push_back(bg.entity[v]);
  }
  point.insert(point.end(), extra_point.begin(), extra_point.end());
  std::vector<Field> cell = {{"face_id", std::vector<double>(bg.tri_face.begin(), bg.tri_face.end())}};
  cell.insert(cell.end(), extra_cell.begin(), extra_cell.end());
  write_vtu(path, bg.xyz, bg.tris, point, cell);
}

void write_background_sizes(const std::string& path, const BackgroundMesh& bg, const SizeMap& m,
                            const WingFeatures* wing) {
  auto shown = [&](const std::vector<double>& h) {
    std::vector<double> out(h.size());
    std::transform(h.begin(), h.end(), out.begin(), [&](double x) { return std::min(x, m.h_max); });
    return out;
  };
  std::vector<double> limit;
  for (Limit l : m.limit) limit.push_back(static_cast<int>(l));
  std::vector<Field> fields = {{"h_curvature", shown(m.h_curvature)}, {"h_proximity", shown(m.h_proximity)},
                               {"h_user", shown(m.h_user)},           {"h_source", shown(m.h_source)},
                               {"h_aero", shown(m.h_aero)},           {"h_initial", m.h_initial},
                               {"h_smoothed", m.h},                   {"limited_by", limit}};
  if (wing) {
    std::vector<double> code(bg.num_vertices(), 0.0);
    for (int v = 0; v < bg.num_vertices(); ++v) {
      if (bg.dim[v] != 1) continue;
      const int c = bg.entity[v];
      if (std::count(wing->leading.begin(), wing->leading.end(), c)) code[v] = 1;
      if (std::count(wing->trailing.begin(), wing->trailing.end(), c)) code[v] = 2;
    }
    // Blunt trailing edges' bases: 3 inside (their creases stay 2); tips' caps 4.
    for (int v = 0; v < bg.num_vertices(); ++v) {
      if (bg.dim[v] != 2) continue;
      for (const WingFeatures::Base& b : wing->bases)
        if (std::count(b.faces.begin(), b.faces.end(), bg.entity[v])) code[v] = 3;
      for (const WingFeatures::Tip& t : wing->tips)
        if (std::count(t.faces.begin(), t.faces.end(), bg.entity[v])) code[v] = 4;
    }
    fields.push_back({"wing_feature", code});
  }
  write_background(path, bg, fields, {{"gradient_ratio", check_gradation(bg, m).triangle_ratio}});
}

}  // namespace sizemesh
