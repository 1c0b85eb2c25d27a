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

void write_background_sizes(const std::string& path, const BackgroundMesh& bg, const SizeMap& m) {
  auto shown = [&](const std::vector<double>& h) {
    std::vector<double> out(h.size());
    std::transform(h.begin(), h.end(), out.begin(), [&](double x) { return std::min(x, m.h_max); });
    return out;
  };
  std::vector<double> limit;
  for (Limit l : m.limit) limit.push_back(static_cast<int>(l));
  write_background(path, bg,
                   {{"h_curvature", shown(m.h_curvature)},
                    {"h_proximity", shown(m.h_proximity)},
                    {"h_user", shown(m.h_user)},
                    {"h_source", shown(m.h_source)},
                    {"h_aero", shown(m.h_aero)},
                    {"h_initial", m.h_initial},
                    {"h_smoothed", m.h},
                    {"limited_by", limit}},
                   {{"gradient_ratio", check_gradation(bg, m).triangle_ratio}});
}

}  // namespace sizemesh
