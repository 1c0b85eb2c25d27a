#include "src/background_output.h"

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

}  // namespace sizemesh
