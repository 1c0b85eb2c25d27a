// The advancing front of one face (the method: mesher/advancing_front.h),
// shared by the files that implement it:
//   advancing_front.cpp  the strategies and the driver: the shortest front
//                        edge first, the step and work budgets, retries;
//   front.cpp            the front itself: edges by node pair, the heap by
//                        metric length, the uv grid and the nearby front;
//   front_check.cpp      whether a candidate triangle may join the front,
//                        in uv and in space;
//   front_step.cpp       one step: the ideal point placed in uv (or in space,
//                        or off a pole), the candidates ranked, the first
//                        acceptable triangle added.
// Internal to those files: the rest of the mesher calls advancing_front().
#pragma once

#include <cstdint>
#include <functional>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mesher/advancing_front.h"
#include "mesher/edge_grid.h"

namespace sizemesh::detail {

struct FrontEdge {
  int a, b;
  bool alive = true;
  int tries = 0;
  double key = 0;  // metric length (space chord / h), shortest first
};

// How demanding a try at an edge is; later tries accept worse triangles.
struct Level {
  double q_min;      // accept the first candidate at least this good
  double cos_min;    // triangle normal against the surface normal
  double near_new;   // a new point keeps this metric distance (in s) from the front
  double radius;     // candidates within this metric distance (in s) of the ideal point
  bool take_best;    // if none reaches q_min, take the best valid one
};
// Tries at one edge, each at the next level of a strategy (advancing_front.cpp).
constexpr int kMaxTries = 6;

class Front {
 public:
  // levels: a strategy's kMaxTries levels, from the first try to the last.
  Front(FaceMesh& fm, FaceSurface& fs, const Level* levels, long long max_steps, bool lenient)
      : fm_(fm), fs_(fs), levels_(levels), max_steps_(max_steps), may_turn_(lenient) {}

  FrontResult run();

  FrontResult& fail(FrontResult& r) const;

 private:
  static uint64_t code(int a, int b) { return (uint64_t(uint32_t(a)) << 32) | uint32_t(b); }
  static uint64_t pair_code(int a, int b) { return a < b ? code(a, b) : code(b, a); }
  // A node's identity in space: its shared id on the boundary (seam copies
  // agree), else its own.
  int identity(int k) const { return fm_.global[k] >= 0 ? fm_.global[k] : (1 << 30) + k; }
  // A new edge between nodes already joined in space would end non-manifold.
  bool used_in_space(int a, int b) const {
    if (fm_.pole[a] || fm_.pole[b]) return false;
    auto it = edge_uses_.find(pair_code(identity(a), identity(b)));
    return it != edge_uses_.end() && it->second > 0;
  }
  void count_uses(int a, int b) {
    if (!fm_.pole[a] && !fm_.pole[b]) ++edge_uses_[pair_code(identity(a), identity(b))];
  }

  bool pole_pair(int a, int b) const {
    return fm_.pole[a] && fm_.pole[b] && fm_.global[a] == fm_.global[b];
  }

  // The front's edges (front.cpp).
  void add_edge(int a, int b);
  // The grid keeps dead edges; rebuilt finer and with the live ones only as the front grows.
  void rebuild_grid();
  void kill_edge(int id) {
    edges_[id].alive = false;
    map_.erase(code(edges_[id].a, edges_[id].b));
    --alive_;
  }
  int find_edge(int a, int b) const {
    auto it = map_.find(code(a, b));
    return it == map_.end() ? -1 : it->second;
  }
  // Alive front edges and their nodes with boxes meeting [lo, hi].
  void gather(const Vec2& lo, const Vec2& hi);

  // A candidate apex: an existing node (id >= 0) or a new point (uv, sample).
  struct Candidate {
    int node = -1;
    Vec2 uv;
    SurfaceSample s;
    double rank = 0;  // metric distance to the ideal point (in s)
    bool in_space = false;  // placed by the space procedure
  };

  // Why a candidate triangle is refused (check() returns these, all negative;
  // the values name the test, they are not ranked).
  enum Refusal : int {
    kFoldedInUv = -1,        // not counter-clockwise in uv
    kCrossesFront = -2,      // a new edge crosses a front edge
    kHoldsFrontNode = -3,    // a front node inside or on the triangle
    kZeroAreaInSpace = -4,   // its corners are collinear in space
    kTurnedAtCorner = -5,    // against the surface normal at a corner
    kPoorShape = -6,         // shape quality not above 1e-6
    kSliverLeft = -7,        // a front node just beside a new edge (a sliver later)
    kNonManifold = -8,       // joins two uv images of one node, or repeats an edge in space
    kTurnedAtCentroid = -9,  // against the surface normal at the uv centroid (or not evaluable there)
    kOutsideOpenAngle = -10, // leaves the unmeshed region through a front node
  };

  // Validity of triangle (a, b, c) against the front, in uv and in space.
  // Returns the shape quality, or a (negative) Refusal (front_check.cpp).
  double check(int a, int b, const Candidate& c, const Level& lv);
  // The new triangle's corner at front node k spans counter-clockwise from
  // direction k->x to k->y (uv; any orientation-preserving map keeps the
  // order, so the metric need not enter). It must lie in an open angle of the
  // front at k: from an outgoing front edge k->n counter-clockwise to an
  // incoming one p->k (the unmeshed side is on the front's left). A node the
  // front touches more than once has several such angles; one must hold it.
  bool within_open_angle(int k, const Vec2& x, const Vec2& y) const;
  // Metric distance (in M) from a new point to the nearby front.
  bool clear_of_front(const Vec2& p, const Eigen::Matrix2d& M, double min_dist) const;

  // One step of the front at edge ei (paper 4.1): ideal point, candidates,
  // best triangle (front_step.cpp).
  bool advance(int ei, const Level& lv);
  // The ideal point off a pole edge, one size from the pole in space, along
  // the edge's normal in uv. The metric on the pole is singular: where the
  // surface closes in like a cone it still has a length across the pole
  // line, but where it closes in quadratically (a tail cone ending in a
  // point whose u-derivative vanishes there too) it has none, and a step
  // in the pole's metric runs off the surface. Bisection on the distance
  // from the pole; `fallback` where the surface cannot be evaluated.
  Vec2 off_pole(const Vec2& m, const SurfaceSample& pole, const Vec2& perp, const Vec2& fallback);
  // Tremel procedure 1: ideal point placed in space off the edge's midpoint,
  // along the surface, then projected onto the surface.
  bool ideal_in_space(int a, int b, const Vec2& m, const SurfaceSample& sm, double s, const Vec2& guess,
                      Candidate& out);

  FaceMesh& fm_;
  FaceSurface& fs_;
  const Level* levels_;
  long long max_steps_;  // tries at front edges, successful or not
  bool may_turn_;        // lenient: the loosest levels may turn a triangle against the surface
  long long steps_ = 0;
  // Front edges and nodes looked at: a step's cost grows with the front near
  // it, so a front crowded into a small part of uv (a corrupt or badly
  // parametrised face) is stopped by this budget before the step budget.
  // Sound faces look at up to ~1700 per step (impeller), against 2000 per
  // budgeted step, and the step budget is 4 times the estimate.
  static constexpr long long kWorkPerStep = 2000;
  static constexpr long long kWorkWarmup = 5000;  // steps before the average is held to kWorkPerStep
  long long work_ = 0;
  std::vector<FrontEdge> edges_;
  std::vector<unsigned> stamp_, node_stamp_;
  unsigned visit_ = 0;
  std::unordered_map<uint64_t, int> map_;
  std::unordered_map<uint64_t, int> edge_uses_;  // triangles per edge in space (identity pairs)
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap_;
  EdgeGrid grid_;
  size_t grid_edges_ = 0;  // edges when the grid was last built
  Vec2 lo_, hi_;
  double aspect_ = 1.0;   // the uv box's length in space along u over that along v (edge_grid.h)
  Vec2 box_lo_, box_hi_;  // the box gather() last covered
  int alive_ = 0;
  int fronts_3d_ = 0;
  std::vector<int> near_edges_, near_nodes_;
};

}  // namespace sizemesh::detail
