// The advancing front's strategies and its driver (the method:
// advancing_front.h; the front's state: front.h): the shortest front edge is
// taken first, tried at the next level of its strategy when it fails, within
// a step budget and a work budget.
#include "mesher/advancing_front.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "mesher/front.h"

namespace sizemesh {
namespace detail {
namespace {

// Strategy 0 prefers well shaped triangles. When its front gets stuck the
// face is meshed again: strategy 1 takes the valid candidate nearest the ideal
// point (it folds less on coarse, strongly curved faces); strategies 2 and 3
// repeat 0 and 1 but at last accept any triangle valid in uv that does not
// turn against the surface at its centroid; a lenient run drops that last
// test too (a few inverted triangles rather than a hole: the optimiser
// repairs what it can and the quality report shows the rest).
constexpr Level kStrategies[kStrategyCount][kMaxTries] = {
    {{0.45, 0.5, 0.5, 1.5, false},
     {0.45, 0.5, 0.5, 1.5, false},
     {0.30, 0.3, 0.4, 2.0, true},
     {0.30, 0.3, 0.4, 2.0, true},
     {0.0, 0.05, 0.25, 4.0, true},
     {0.0, 0.0, 0.15, 8.0, true}},
    {{0.05, 0.5, 0.5, 1.5, false},
     {0.05, 0.5, 0.5, 1.5, false},
     {0.02, 0.3, 0.4, 2.0, true},
     {0.02, 0.3, 0.4, 2.0, true},
     {0.0, 0.05, 0.25, 4.0, true},
     {0.0, 0.0, 0.15, 8.0, true}},
    {{0.45, 0.5, 0.5, 1.5, false},
     {0.45, 0.5, 0.5, 1.5, false},
     {0.30, 0.3, 0.4, 2.0, true},
     {0.0, 0.05, 0.25, 4.0, true},
     {0.0, 0.0, 0.15, 8.0, true},
     {0.0, -2.0, 0.1, 8.0, true}},
    {{0.05, 0.3, 0.4, 2.0, false},
     {0.02, 0.1, 0.3, 2.0, true},
     {0.0, 0.0, 0.25, 4.0, true},
     {0.0, -0.2, 0.15, 4.0, true},
     {0.0, -0.5, 0.15, 8.0, true},
     {0.0, -2.0, 0.1, 8.0, true}},
};

}  // namespace

FrontResult Front::run() {
  FrontResult r;
  int n_edges = 0;
  Vec2 lo = fm_.uv[0], hi = fm_.uv[0];
  for (const auto& loop : fm_.loops) {
    n_edges += static_cast<int>(loop.size());
    for (int i : loop) {
      lo = lo.cwiseMin(fm_.uv[i]);
      hi = hi.cwiseMax(fm_.uv[i]);
    }
  }
  lo_ = lo;
  hi_ = hi;
  // The box's length in space along u against v, from the surface's mean
  // speeds at 5 x 5 points inside it (the boundary alone misleads: a
  // sphere's pole edges have no length in space).
  double speed_u = 0, speed_v = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      const Vec2 uv(lo.x() + (hi.x() - lo.x()) * (i + 0.5) / 5, lo.y() + (hi.y() - lo.y()) * (j + 0.5) / 5);
      try {
        const SurfaceSample q = fs_.eval_shape(uv);
        if (q.du.allFinite() && q.dv.allFinite()) speed_u += q.du.norm(), speed_v += q.dv.norm();
      } catch (const EvaluationError&) {  // outside what the surface evaluates: not counted
      }
    }
  aspect_ = speed_u > 0 && speed_v > 0 && hi.y() > lo.y() ? (hi.x() - lo.x()) * speed_u / ((hi.y() - lo.y()) * speed_v)
                                                          : 1.0;
  grid_.init(lo, hi, n_edges, aspect_);
  grid_edges_ = std::max<size_t>(n_edges, 64);
  // Triangles on each edge in space (by node identity, across seams): a
  // boundary edge has one on the other face, a seam edge none yet.
  for (const auto& loop : fm_.loops)
    for (size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i], b = loop[(i + 1) % loop.size()];
      add_edge(a, b);
      if (!fm_.pole[a] && !fm_.pole[b]) {
        int& uses = edge_uses_[pair_code(identity(a), identity(b))];
        uses = uses == 0 ? 1 : 0;
      }
    }

  while (!heap_.empty()) {
    const auto [key, ei] = heap_.top();
    heap_.pop();
    FrontEdge& e = edges_[ei];
    if (!e.alive || e.key != key) continue;
    if (++steps_ > max_steps_) {
      r.reason = "the advancing front spent its work budget of " + std::to_string(max_steps_) + " steps (" +
                 std::to_string(alive_) + " front edges left)";
      return fail(r);
    }
    // Work: within the face's budget, and (past a warm-up) within
    // kWorkPerStep per step on average: a front crowding into a corner of
    // its domain looks at ten times that and stops early.
    if (work_ > kWorkPerStep * std::min(max_steps_, std::max(steps_, kWorkWarmup))) {
      r.reason = "the advancing front spent its work budget after " + std::to_string(steps_) + " steps (" +
                 std::to_string(work_) + " front edges and nodes looked at, " + std::to_string(alive_) +
                 " front edges left)";
      return fail(r);
    }
    if (advance(ei, levels_[e.tries])) continue;
    FrontEdge& e2 = edges_[ei];
    if (++e2.tries >= kMaxTries) {
      r.reason = "front could not advance from an edge after " + std::to_string(kMaxTries) +
                 " tries (" + std::to_string(alive_) + " front edges left)";
      return fail(r);
    }
    e2.key += 1.0 + e2.tries;  // try the rest of the front first
    heap_.push({e2.key, ei});
  }
  r.ok = alive_ == 0;
  if (!r.ok) r.reason = "front left open";
  r.fronts_3d = fronts_3d_;
  r.steps = steps_;
  r.work = work_;
  return r;
}

FrontResult& Front::fail(FrontResult& r) const {
  r.fronts_3d = fronts_3d_;
  r.steps = steps_;
  r.work = work_;
  for (const FrontEdge& e : edges_)
    if (e.alive) r.open_edges.push_back({e.a, e.b});
  return r;
}

}  // namespace detail

long long front_step_budget(double expected_triangles, int boundary_nodes) {
  const double n = boundary_nodes;
  // With no estimate (a face without background triangles) a disc bounded by
  // n nodes holds about n^2 / 5 triangles.
  const double expected = expected_triangles > 0 ? expected_triangles : 0.2 * n * n;
  return static_cast<long long>(std::min(4.0 * expected + 10.0 * n + 1000.0, 4e9));
}

FrontResult advancing_front(FaceMesh& fm, FaceSurface& fs, int strategy, long long max_steps, bool lenient) {
  detail::Front front(fm, fs, detail::kStrategies[std::clamp(strategy, 0, kStrategyCount - 1)], max_steps, lenient);
  return front.run();
}

}  // namespace sizemesh
