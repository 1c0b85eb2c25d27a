// The size map graded away from the junction at the gradient bound (JunctionGradedSize).
#pragma once

#include <map>
#include <vector>

#include "core/geometry.h"
#include "core/size_field.h"

namespace sizemesh::cut_faces_detail {

// The size map, bounded near the junction by the sizes along it grown at
// the face's gradient bound (Eq. 12, |h_i - h_j| <= ln(beta) l_ij, with the
// straight distance for the length): two components' size maps meet at a
// junction neither saw, and a face coarse where the other is fine would
// jump from the junction's size to its own within one element. It keeps
// the size map's accuracy rules.
class JunctionGradedSize final : public SizeField {
 public:
  JunctionGradedSize(const Geometry& g, const SizeField& base, const std::vector<double>& slope)
      : g_(g), base_(base), slope_(slope) {
    set_accuracy(base.accuracy());
  }
  void add(int face, const Vec3& x, double size);
  // Seeds by size, for the early stop in bound().
  void finish();
  double at(int face, const Vec2& uv, int& hint) const override;
  double at_xyz(const Vec3& x) const override;  // no face: the size map's

 private:
  struct Seed {
    double size;
    Vec3 x;
  };
  static double bound(const std::vector<Seed>& seeds, double slope, const Vec3& x, double h);
  const Geometry& g_;
  const SizeField& base_;
  const std::vector<double>& slope_;
  std::map<int, std::vector<Seed>> seeds_;
};

}  // namespace sizemesh::cut_faces_detail
