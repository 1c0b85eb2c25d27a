#include "sizing/limit_at.h"

namespace sizemesh {

int limit_at(const SizeQuery& q, const BackgroundMesh& bg, const SizeMap& m, int face, const Vec2& uv,
             const Vec3& xyz, int& hint) {
  if (face < 1 || face > static_cast<int>(bg.patches.size())) return -1;
  const SizeQuery::Hit hit = q.locate(face, uv, hint);
  const FacePatch& patch = bg.patches[face - 1];
  if (hit.tri < 0 || hit.tri >= static_cast<int>(patch.tris.size())) return -1;
  hint = hit.tri;
  int best = -1;
  double best_d = 0;
  for (int local : patch.tris[hit.tri]) {
    const int v = patch.vertex[local];
    const double d = (bg.xyz[v] - xyz).squaredNorm();
    if (best < 0 || d < best_d) best = v, best_d = d;
  }
  return best >= 0 && best < static_cast<int>(m.limit.size()) ? static_cast<int>(m.limit[best]) : -1;
}

}  // namespace sizemesh
