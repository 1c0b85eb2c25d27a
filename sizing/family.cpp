#include "sizing/family.h"

#include <algorithm>
#include <cmath>

namespace sizemesh {

double family_scale(int level, int levels, double ratio) {
  const int middle = (levels + 1) / 2;
  return std::pow(ratio, 0.5 * (middle - level));
}

SizeMap scaled_map(const SizeMap& m, double s) {
  SizeMap out = m;
  for (std::vector<double>* v : {&out.h_curvature, &out.h_proximity, &out.h_user, &out.h_source, &out.h_initial,
                                 &out.h, &out.h_cap})
    for (double& x : *v) x *= s;  // kNoLimit stays infinite
  out.h_min *= s;
  out.h_max *= s;
  return out;
}

SizingParams scaled_rules(const SizingParams& p, double s) {
  SizingParams out = p;
  out.deviation *= s * s;
  auto turn = [&](double deg) { return std::min(deg * s, 179.0); };
  out.phi_c_deg = turn(out.phi_c_deg);
  for (auto& [id, deg] : out.face_phi_c_deg) deg = turn(deg);
  for (auto& [id, deg] : out.curve_phi_c_deg) deg = turn(deg);
  return out;
}

}  // namespace sizemesh
