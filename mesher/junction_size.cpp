// The junction-graded size map's seeds and its bound (JunctionGradedSize).
#include "mesher/junction_size.h"

#include <algorithm>
#include <cmath>

namespace sizemesh::cut_faces_detail {

void JunctionGradedSize::add(int face, const Vec3& x, double size) {
  if (face > 0 && face < static_cast<int>(slope_.size()) && slope_[face] > 0 && size > 0 && std::isfinite(size))
    seeds_[face].push_back({size, x});
}

void JunctionGradedSize::finish() {
  for (auto& [f, list] : seeds_)
    std::sort(list.begin(), list.end(), [](const Seed& a, const Seed& b) { return a.size < b.size; });
}

double JunctionGradedSize::at(int face, const Vec2& uv, int& hint) const {
  const double h = base_.at(face, uv, hint);
  const auto it = seeds_.find(face);
  if (it == seeds_.end() || !(h > it->second.front().size)) return h;
  return bound(it->second, slope_[face], g_.eval_face(face, uv).p, h);
}

double JunctionGradedSize::at_xyz(const Vec3& x) const { return base_.at_xyz(x); }

double JunctionGradedSize::bound(const std::vector<Seed>& seeds, double slope, const Vec3& x, double h) {
  for (const Seed& s : seeds) {
    if (s.size >= h) break;
    h = std::min(h, s.size + slope * (x - s.x).norm());
  }
  return h;
}

}  // namespace sizemesh::cut_faces_detail
