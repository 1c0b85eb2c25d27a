#include "mesher/ops/rescue.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/predicates.h"

namespace sizemesh {
namespace ops {
namespace {

constexpr double kRescueBelow = 15;

}  // namespace

NodeMove check_rescue(const FaceMesh& fm, const FaceSurface& fs, const Balls& balls, int i) {
  double smallest = 180;  // from the positions alone, before any surface evaluation
  for (int e = balls.start[i]; e < balls.start[i + 1]; ++e) {
    const auto& t = fm.tris[balls.tri_of[e]];
    smallest = std::min(smallest, min_angle_deg(fm.s[t[0]].p, fm.s[t[1]].p, fm.s[t[2]].p));
  }
  if (!(smallest < kRescueBelow)) return {};
  Vec2 uv = fm.uv[i];
  SurfaceSample s = fm.s[i];
  std::vector<char> lenient;  // triangles that fail the shape's validity as they are
  for (int e = balls.start[i]; e < balls.start[i + 1]; ++e) {
    const auto& t = fm.tris[balls.tri_of[e]];
    lenient.push_back(!fm.pole_triangle(t) && shape(fm, fs, t) < 0);
  }
  BallMeasure best = measure_ball(fm, fs, balls, i, uv, s, &lenient);
  if (!best.valid || !(best.angle < kRescueBelow)) return {};
  const BallMeasure start_value = best;
  double step = 0;  // a third of the mean edge in uv
  for (int e = balls.start[i]; e < balls.start[i + 1]; ++e)
    for (int v : fm.tris[balls.tri_of[e]]) step += (fm.uv[v] - uv).norm();
  step /= 6.0 * (balls.start[i + 1] - balls.start[i]);
  for (int it = 0; it < 40 && step > 0; ++it) {
    bool improved = false;
    Vec2 best_uv = uv;
    SurfaceSample best_s = s;
    for (int d = 0; d < 8; ++d) {
      const double a = d * kPi / 4;
      const Vec2 trial = uv + step * Vec2(std::cos(a), std::sin(a));
      SurfaceSample ts;
      try {
        ts = fs.eval_shape(trial);
      } catch (const EvaluationError&) {
        continue;
      }
      ts.h = fm.s[i].h;
      const BallMeasure v = measure_ball(fm, fs, balls, i, trial, ts, &lenient);
      if (v.valid && v.better_than(best, 1e-9)) {
        best = v;
        best_uv = trial;
        best_s = ts;
        improved = true;
      }
    }
    if (improved) {
      uv = best_uv;
      s = best_s;
    } else {
      step *= 0.5;
    }
  }
  // Kept when it leaves fewer thin triangles, or none and a larger smallest
  // angle: a thin triangle traded for another one would only move it.
  if (best.thin < start_value.thin || (start_value.thin == 0 && best.better_than(start_value, 1e-6)))
    return {true, uv, s};
  return {};
}

}  // namespace ops

int rescue_thin_triangles(FaceMesh& fm, const FaceSurface& fs) {
  const ops::Balls balls(fm);
  int moved = 0;
  for (int i = 0; i < fm.num_nodes(); ++i) {
    if (fm.boundary(i) || balls.start[i] == balls.start[i + 1]) continue;
    const ops::NodeMove m = ops::check_rescue(fm, fs, balls, i);
    if (!m.ok) continue;
    ops::apply_move(fm, i, m);
    ++moved;
  }
  return moved;
}

}  // namespace sizemesh
