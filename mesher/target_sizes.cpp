#include "mesher/target_sizes.h"

namespace sizemesh {

std::vector<double> target_sizes(const SurfaceMesh& mesh, const SizeField& h) {
  std::vector<double> target(mesh.xyz.size(), -1.0);
  int hint = -1;
  for (size_t t = 0; t < mesh.tris.size(); ++t) {
    if (t > 0 && mesh.tri_face[t] != mesh.tri_face[t - 1]) hint = -1;  // hints are per face
    for (int k = 0; k < 3; ++k) {
      double& h_node = target[mesh.tris[t][k]];
      if (h_node < 0) h_node = h.at(mesh.tri_face[t], mesh.tri_uv[t][k], hint);
    }
  }
  return target;
}

}  // namespace sizemesh
