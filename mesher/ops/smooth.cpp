#include "mesher/ops/smooth.h"

#include <algorithm>
#include <cmath>

namespace sizemesh::ops {

NodeMove check_smooth(const FaceMesh& fm, const FaceSurface& fs, const Balls& balls, int i) {
  const std::vector<int>&start = balls.start, &tri_of = balls.tri_of;
  Vec3 target = Vec3::Zero();
  int cnt = 0;
  double old_q = 2;
  for (int e = start[i]; e < start[i + 1]; ++e) {
    const auto& tr = fm.tris[tri_of[e]];
    for (int v : tr)
      if (v != i) {
        target += fm.s[v].p;
        ++cnt;
      }
    if (!fm.pole_triangle(tr)) old_q = std::min(old_q, shape(fm, fs, tr));
  }
  target /= cnt;
  const SurfaceSample& si = fm.s[i];
  Eigen::Matrix<double, 3, 2> J;
  J.col(0) = si.du;
  J.col(1) = si.dv;
  const Eigen::Matrix2d JtJ = J.transpose() * J;
  if (!(std::abs(JtJ.determinant()) > 1e-300)) return {};
  const Vec2 step = JtJ.ldlt().solve(J.transpose() * (target - si.p));
  if (!std::isfinite(step.x()) || !std::isfinite(step.y())) return {};
  for (double f : {1.0, 0.5}) {
    const Vec2 uv = fm.uv[i] + f * step;
    SurfaceSample s;
    try {
      s = fs.eval_shape(uv);
    } catch (const EvaluationError&) {
      continue;  // outside what the surface can evaluate: stay
    }
    s.h = si.h;
    if (!ball_keeps_shape(fm, fs, balls, i, uv, s, old_q)) continue;
    return {true, uv, s};
  }
  return {};
}

int smooth_sweep(FaceMesh& fm, const FaceSurface& fs) {
  const int n = fm.num_nodes();
  const Balls balls(fm);
  const std::vector<int>& start = balls.start;
  int moved = 0;
  for (int i = 0; i < n; ++i) {
    if (fm.boundary(i) || start[i] == start[i + 1]) continue;
    const NodeMove m = check_smooth(fm, fs, balls, i);
    if (!m.ok) continue;
    apply_move(fm, i, m);
    ++moved;
  }
  return moved;
}

}  // namespace sizemesh::ops
