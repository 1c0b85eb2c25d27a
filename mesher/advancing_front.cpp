#include "mesher/advancing_front.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <queue>
#include <unordered_map>

#include "mesher/edge_grid.h"
#include "geometry/predicates.h"

namespace sizemesh {
namespace {


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
// Strategy 0 prefers well shaped triangles. When its front gets stuck the
// face is meshed again: strategy 1 takes the valid candidate nearest the ideal
// point (it folds less on coarse, strongly curved faces); strategies 2 and 3
// repeat 0 and 1 but at last accept any triangle valid in uv that does not
// turn against the surface at its centroid; a lenient run drops that last
// test too (a few inverted triangles rather than a hole: the optimiser
// repairs what it can and the quality report shows the rest).
constexpr int kMaxTries = 6;
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

class Front {
 public:
  Front(FaceMesh& fm, FaceSurface& fs, int strategy, long long max_steps, bool lenient)
      : fm_(fm), fs_(fs), levels_(kStrategies[strategy]), max_steps_(max_steps), may_turn_(lenient) {}

  FrontResult run() {
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
    grid_.init(lo, hi, n_edges);
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
    return r;
  }

  FrontResult& fail(FrontResult& r) const {
    r.fronts_3d = fronts_3d_;
    r.steps = steps_;
    for (const FrontEdge& e : edges_)
      if (e.alive) r.open_edges.push_back({e.a, e.b});
    return r;
  }

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

  void add_edge(int a, int b) {
    FrontEdge e;
    e.a = a;
    e.b = b;
    const double ha = fm_.s[a].h, hb = fm_.s[b].h;
    e.key = pole_pair(a, b) ? 0.0 : (fm_.s[b].p - fm_.s[a].p).norm() / (0.5 * (ha + hb));
    const int id = static_cast<int>(edges_.size());
    edges_.push_back(e);
    stamp_.push_back(0);
    map_[code(a, b)] = id;
    grid_.insert(id, fm_.uv[a], fm_.uv[b]);
    heap_.push({e.key, id});
    ++alive_;
    if (edges_.size() >= 4 * grid_edges_) rebuild_grid();
  }
  // The grid keeps dead edges; rebuilt finer and with the live ones only as the front grows.
  void rebuild_grid() {
    grid_edges_ = edges_.size();
    grid_.init(lo_, hi_, static_cast<int>(edges_.size()));
    for (int id = 0; id < static_cast<int>(edges_.size()); ++id)
      if (edges_[id].alive) grid_.insert(id, fm_.uv[edges_[id].a], fm_.uv[edges_[id].b]);
  }
  void kill_edge(int id) {
    edges_[id].alive = false;
    map_.erase(code(edges_[id].a, edges_[id].b));
    --alive_;
  }
  int find_edge(int a, int b) const {
    auto it = map_.find(code(a, b));
    return it == map_.end() ? -1 : it->second;
  }

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
  // Returns the shape quality, or a (negative) Refusal.
  double check(int a, int b, const Candidate& c, const Level& lv) {
    const Vec2& ua = fm_.uv[a];
    const Vec2& ub = fm_.uv[b];
    const Vec2& uc = c.uv;
    // A front neighbour taken as apex may lie outside the gathered box: the
    // front its new edges could cross is gathered first.
    if ((uc.array() < box_lo_.array()).any() || (uc.array() > box_hi_.array()).any())
      gather(box_lo_.cwiseMin(uc), box_hi_.cwiseMax(uc));
    const double o = orient(ua, ub, uc);
    const double scale = (ub - ua).norm() * ((uc - ua).norm() + (uc - ub).norm());
    if (!(o > 1e-10 * scale)) return kFoldedInUv;
    // Seam copies: no triangle joins two uv images of one node, and no inner
    // edge repeats a boundary edge in space (it would be non-manifold).
    if (c.node >= 0 && fm_.global[c.node] >= 0) {
      const int gc = fm_.global[c.node];
      if ((gc == fm_.global[a] && !pole_pair(a, c.node)) || (gc == fm_.global[b] && !pole_pair(b, c.node)))
        return kNonManifold;
    }
    // The triangle lies in the unmeshed region at each of its corners: an edge
    // leaving a front node outside the node's open angle crosses no front edge
    // yet escapes through the node (into the meshed part or out of the domain).
    if (!within_open_angle(a, ub, uc) || !within_open_angle(b, uc, ua) ||
        (c.node >= 0 && !within_open_angle(c.node, ua, ub)))
      return kOutsideOpenAngle;
    work_ += static_cast<long long>(near_edges_.size() + near_nodes_.size());
    // New edges must cross no front edge.
    const bool new_ac = c.node < 0 || find_edge(c.node, a) < 0;
    const bool new_cb = c.node < 0 || find_edge(b, c.node) < 0;
    if (c.node >= 0 && ((new_ac && used_in_space(a, c.node)) || (new_cb && used_in_space(c.node, b))))
      return kNonManifold;
    for (int ei : near_edges_) {
      const FrontEdge& e = edges_[ei];
      if (!e.alive) continue;
      const Vec2& p = fm_.uv[e.a];
      const Vec2& q = fm_.uv[e.b];
      if (new_ac && e.a != a && e.b != a && e.a != c.node && e.b != c.node &&
          segments_meet(ua, uc, p, q))
        return kCrossesFront;
      if (new_cb && e.a != b && e.b != b && e.a != c.node && e.b != c.node &&
          segments_meet(uc, ub, p, q))
        return kCrossesFront;
    }
    // No front node inside or on the triangle.
    const double tol = -1e-10 * o;
    for (int k : near_nodes_) {
      if (k == a || k == b || k == c.node) continue;
      const Vec2& uk = fm_.uv[k];
      if (orient(ua, ub, uk) >= tol && orient(ub, uc, uk) >= tol && orient(uc, ua, uk) >= tol)
        return kHoldsFrontNode;
      // Nor (in space) just beside a new edge: it would leave a sliver for later.
      if (lv.cos_min > -1 && !fm_.pole[k] && ((new_ac && near_segment(fm_.s[a].p, c.s.p, fm_.s[k].p)) ||
                           (new_cb && near_segment(c.s.p, fm_.s[b].p, fm_.s[k].p))))
        return kSliverLeft;
    }
    // Space: the triangle faces the way of the surface normal (Tremel procedure 2).
    const bool pole_tri = pole_pair(a, b) || (c.node >= 0 && (pole_pair(b, c.node) || pole_pair(c.node, a)));
    if (pole_tri) return 0.8;
    const Vec3& pa = fm_.s[a].p;
    const Vec3& pb = fm_.s[b].p;
    const Vec3& pc = c.s.p;
    const Vec3 nt = (pb - pa).cross(pc - pa);
    const double lt = nt.norm();
    if (!(lt > 0)) return kZeroAreaInSpace;
    const Vec3* normals[3] = {&fm_.s[a].n, &fm_.s[b].n, &c.s.n};  // zero on poles
    for (const Vec3* n : normals)
      if (n->squaredNorm() > 0 && nt.dot(*n) <= lv.cos_min * lt) return kTurnedAtCorner;
    const double q = triangle_quality(pa, pb, pc);
    if (!(q > 1e-6)) return kPoorShape;
    // And at the uv centroid, where a curved surface may turn away between
    // corners: never against the normal there (the quality report's test for
    // an inverted triangle), but in a lenient run's loosest levels.
    if (lv.cos_min > -1 || !may_turn_) {
      Vec3 nc;
      try {
        nc = fs_.eval_shape((ua + ub + uc) / 3.0).n;
      } catch (const EvaluationError&) {
        return kTurnedAtCentroid;
      }
      if (nc.squaredNorm() > 0 && nt.dot(nc) <= std::max(lv.cos_min, 0.0) * lt) return kTurnedAtCentroid;
    }
    return q;
  }

  // Counter-clockwise angle from direction u to direction v, in [0, 2 pi).
  static double ccw_angle(const Vec2& u, const Vec2& v) {
    const double t = std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
    return t < 0 ? t + 2 * kPi : t;
  }
  // The new triangle's corner at front node k spans counter-clockwise from
  // direction k->x to k->y (uv; any orientation-preserving map keeps the
  // order, so the metric need not enter). It must lie in an open angle of the
  // front at k: from an outgoing front edge k->n counter-clockwise to an
  // incoming one p->k (the unmeshed side is on the front's left). A node the
  // front touches more than once has several such angles; one must hold it.
  bool within_open_angle(int k, const Vec2& x, const Vec2& y) const {
    const Vec2& uk = fm_.uv[k];
    const Vec2 dx = x - uk, dy = y - uk;
    constexpr double eps = 1e-9;  // collinear directions (closing a loop) pass
    bool touched = false;
    for (int eo : near_edges_) {
      if (!edges_[eo].alive || edges_[eo].a != k) continue;
      const Vec2 dn = fm_.uv[edges_[eo].b] - uk;
      for (int ei : near_edges_) {
        if (!edges_[ei].alive || edges_[ei].b != k) continue;
        touched = true;
        const double open = ccw_angle(dn, fm_.uv[edges_[ei].a] - uk);
        const double ax = ccw_angle(dn, dx), ay = ccw_angle(dn, dy);
        const double ax0 = ax > 2 * kPi - eps ? 0.0 : ax;  // along k->n
        if (ax0 <= ay + eps && ay <= open + eps) return true;
      }
    }
    return !touched;  // no front edges seen at k: nothing to test against
  }

  // Point x within a small fraction of the segment's length of segment pq (space).
  static bool near_segment(const Vec3& p, const Vec3& q, const Vec3& x) {
    const Vec3 d = q - p;
    const double l2 = d.squaredNorm();
    if (!(l2 > 0)) return false;
    const double t = (x - p).dot(d) / l2;
    if (t <= 0.02 || t >= 0.98) return false;
    return (x - p - t * d).squaredNorm() < 0.03 * 0.03 * l2;
  }

  // Metric distance (in M) from a new point to the nearby front.
  bool clear_of_front(const Vec2& p, const Eigen::Matrix2d& M, double min_dist) const {
    const double d2 = min_dist * min_dist;
    for (int k : near_nodes_) {
      const Vec2 d = fm_.uv[k] - p;
      if (d.dot(M * d) < d2) return false;
    }
    for (int ei : near_edges_) {
      const FrontEdge& e = edges_[ei];
      if (!e.alive) continue;
      const Vec2& q0 = fm_.uv[e.a];
      const Vec2 dq = fm_.uv[e.b] - q0;
      const double l2 = dq.dot(M * dq);
      double t = l2 > 0 ? (p - q0).dot(M * dq) / l2 : 0;
      t = std::clamp(t, 0.0, 1.0);
      const Vec2 d = q0 + t * dq - p;
      if (d.dot(M * d) < 0.49 * d2) return false;
    }
    return true;
  }

  // One step of the front at edge ei (paper 4.1): ideal point, candidates, best triangle.
  bool advance(int ei, const Level& lv) {
    const int a = edges_[ei].a, b = edges_[ei].b;
    const Vec2 ua = fm_.uv[a], ub = fm_.uv[b];
    const Vec2 e = ub - ua;
    const Vec2 m = 0.5 * (ua + ub);
    const SurfaceSample sm = fs_.eval(m);
    const Eigen::Matrix2d Mm = sm.metric();
    const bool pole_edge = pole_pair(a, b);
    const Vec2 perp(-e.y(), e.x());

    // Ideal point in uv: equilateral in the metric, side s (unit, bounded by the edge's length).
    const double L = pole_edge ? 0.0 : std::sqrt(e.dot(Mm * e));
    const double s = pole_edge ? 1.0 : std::min(std::max(1.0, 0.55 * L), 2.0 * L);
    const double height = pole_edge ? 1.0 : std::sqrt(std::max(s * s - 0.25 * L * L, 0.05 * s * s));
    Vec2 d = pole_edge ? perp : Vec2(Mm.inverse() * perp);
    const double dl = std::sqrt(std::max(d.dot(Mm * d), 1e-300));
    d /= dl;
    Candidate ideal;
    ideal.uv = m + height * d;
    if (pole_edge) ideal.uv = off_pole(m, sm, perp, ideal.uv);
    bool ideal_ok = std::isfinite(ideal.uv.x()) && std::isfinite(ideal.uv.y());
    try {  // the ideal point may fall outside the surface's parameter range
      if (ideal_ok) ideal.s = fs_.eval(ideal.uv);
    } catch (const EvaluationError&) {
      ideal_ok = false;
    }
    const Eigen::Matrix2d Mp = ideal_ok ? ideal.s.metric() : Mm;
    // Ranking metric: the midpoint's, except on a pole where it is singular.
    const Eigen::Matrix2d M = pole_edge ? Mp : Mm;

    // Nearby front: a box holding the metric ball of radius lv.radius * s around the ideal point.
    const double r = lv.radius * s;
    const Eigen::Matrix2d Minv = M.inverse();
    Vec2 half(r * std::sqrt(std::max(Minv(0, 0), 0.0)), r * std::sqrt(std::max(Minv(1, 1), 0.0)));
    const Vec2 span = hi_ - lo_;
    half = half.cwiseMin(span);
    Vec2 blo = ideal.uv - half, bhi = ideal.uv + half;
    blo = blo.cwiseMin(ua).cwiseMin(ub);
    bhi = bhi.cwiseMax(ua).cwiseMax(ub);
    if (!std::isfinite(blo.x()) || !std::isfinite(blo.y()) || !std::isfinite(bhi.x()) ||
        !std::isfinite(bhi.y())) {
      blo = lo_;
      bhi = hi_;
    }
    gather(blo, bhi);
    // New points: the uv ideal point, and when it is poor the one placed in space.
    const double new_rank = 0.55;
    const double q_ideal = ideal_ok ? check(a, b, ideal, lv) : -1;
    Candidate c3;
    bool have_3d = false;
    if (!pole_edge && q_ideal < 0.6 && ideal_in_space(a, b, m, sm, s, ideal_ok ? ideal.uv : m, c3)) {
      have_3d = true;
      c3.in_space = true;
      c3.rank = new_rank + (q_ideal >= 0 ? 1e-9 : -1e-9);
      if (c3.uv.x() < blo.x() || c3.uv.y() < blo.y() || c3.uv.x() > bhi.x() || c3.uv.y() > bhi.y())
        gather(blo.cwiseMin(c3.uv), bhi.cwiseMax(c3.uv));
    }

    std::vector<Candidate> cands;
    // Front neighbours of the edge are always candidates (they close loops).
    int prev = -1, next = -1;
    for (int ej : near_edges_) {
      if (edges_[ej].a == b) next = edges_[ej].b;
      if (edges_[ej].b == a) prev = edges_[ej].a;
    }
    for (int k : near_nodes_) {
      if (k == a || k == b) continue;
      if (orient(ua, ub, fm_.uv[k]) <= 0) continue;
      const Vec2 dk = fm_.uv[k] - ideal.uv;
      const double dist = std::sqrt(std::max(dk.dot(M * dk), 0.0)) / s;
      if (dist > lv.radius && k != prev && k != next) continue;
      Candidate c;
      c.node = k;
      c.uv = fm_.uv[k];
      c.s = fm_.s[k];
      c.rank = dist;
      cands.push_back(c);
    }
    if (ideal_ok && clear_of_front(ideal.uv, M, lv.near_new * s)) {
      ideal.rank = new_rank;
      cands.push_back(ideal);
    }
    if (have_3d && clear_of_front(c3.uv, M, lv.near_new * s)) cands.push_back(c3);
    std::stable_sort(cands.begin(), cands.end(),
                     [](const Candidate& x, const Candidate& y) { return x.rank < y.rank; });

    int best = -1;
    double best_q = -1;
    for (size_t i = 0; i < cands.size(); ++i) {
      const bool is_ideal = cands[i].node < 0 && !cands[i].in_space;
      const double q = is_ideal ? q_ideal : check(a, b, cands[i], lv);
      if (q < 0) continue;
      if (q >= lv.q_min) {
        best = static_cast<int>(i);
        best_q = q;
        break;
      }
      if (lv.take_best && q > best_q) {
        best_q = q;
        best = static_cast<int>(i);
      }
    }
    if (best < 0) return false;
    if (best_q < lv.q_min && !lv.take_best) return false;
    Candidate& c = cands[best];
    int cn = c.node;
    if (cn < 0) {
      cn = fm_.add_node(c.uv, c.s, -1);
      if (c.in_space) ++fronts_3d_;
    }
    fm_.tris.push_back({a, b, cn});
    count_uses(a, b);
    count_uses(b, cn);
    count_uses(cn, a);
    kill_edge(ei);
    const int ca = find_edge(cn, a);
    if (ca >= 0) kill_edge(ca); else add_edge(a, cn);
    const int bc = find_edge(b, cn);
    if (bc >= 0) kill_edge(bc); else add_edge(cn, b);
    return true;
  }

  // The ideal point off a pole edge, one size from the pole in space, along
  // the edge's normal in uv. The metric on the pole is singular: where the
  // surface closes in like a cone it still has a length across the pole
  // line, but where it closes in quadratically (a tail cone ending in a
  // point whose u-derivative vanishes there too) it has none, and a step
  // in the pole's metric runs off the surface. Bisection on the distance
  // from the pole; `fallback` where the surface cannot be evaluated.
  Vec2 off_pole(const Vec2& m, const SurfaceSample& pole, const Vec2& perp, const Vec2& fallback) {
    const double reach = (hi_ - lo_).norm();
    if (!(perp.norm() > 0) || !(reach > 0)) return fallback;
    const Vec2 dir = perp.normalized();
    // Distance from the pole at uv m + t dir, in sizes wanted there.
    auto sizes_away = [&](double t) {
      const SurfaceSample q = fs_.eval(m + t * dir);
      return (q.p - pole.p).norm() / q.h;
    };
    try {
      // A bracket [lo, hi] from a thousandth of the face's uv span, halved
      // or doubled, then halved to a hundredth of its length.
      double lo = 0, hi = 1e-3 * reach;
      if (sizes_away(hi) >= 1) {
        for (int it = 0; it < 60 && lo == 0; ++it) {
          if (sizes_away(0.5 * hi) < 1) lo = 0.5 * hi;
          else hi *= 0.5;
        }
      } else {
        while (sizes_away(hi) < 1) {
          if (hi >= reach) return fallback;
          lo = hi;
          hi = std::min(2 * hi, reach);
        }
      }
      for (int it = 0; it < 20 && hi - lo > 0.01 * hi; ++it) {
        const double mid = 0.5 * (lo + hi);
        (sizes_away(mid) < 1 ? lo : hi) = mid;
      }
      return m + hi * dir;
    } catch (const EvaluationError&) {
      return fallback;
    }
  }

  // Tremel procedure 1: ideal point placed in space off the edge's midpoint,
  // along the surface, then projected onto the surface.
  bool ideal_in_space(int a, int b, const Vec2& m, const SurfaceSample& sm, double s, const Vec2& guess,
                      Candidate& out) {
    const Vec3& pa = fm_.s[a].p;
    const Vec3& pb = fm_.s[b].p;
    const Vec3 ab = pb - pa;
    if (sm.n.norm() == 0 || ab.norm() == 0) return false;
    Vec3 t = sm.n.cross(ab);
    if (t.norm() == 0) return false;
    t.normalize();
    const double side = s * sm.h;
    const double height = std::sqrt(std::max(side * side - 0.25 * ab.squaredNorm(), 0.05 * side * side));
    const Vec3 target = 0.5 * (pa + pb) + height * t;
    Vec2 uv = std::isfinite(guess.x()) && std::isfinite(guess.y()) ? guess : m;
    try {
      if (!fs_.project(target, uv)) return false;
      out.uv = uv;
      out.s = fs_.eval(uv);
    } catch (const EvaluationError&) {
      return false;
    }
    out.node = -1;
    return (out.s.p - target).norm() <= 0.5 * height;
  }

  // Alive front edges and their nodes with boxes meeting [lo, hi].
  void gather(const Vec2& lo, const Vec2& hi) {
    box_lo_ = lo;
    box_hi_ = hi;
    ++visit_;
    near_edges_.clear();
    near_nodes_.clear();
    grid_.query(
        lo, hi, [&](int e) { return ++work_, edges_[e].alive; },
        [&](int e) {
          if (stamp_[e] == visit_) return;
          stamp_[e] = visit_;
          near_edges_.push_back(e);
        });
    if (node_stamp_.size() < fm_.uv.size()) node_stamp_.resize(fm_.uv.size() + 1024, 0);
    for (int ei : near_edges_)
      for (int k : {edges_[ei].a, edges_[ei].b})
        if (node_stamp_[k] != visit_) {
          node_stamp_[k] = visit_;
          near_nodes_.push_back(k);
        }
  }

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
  Vec2 box_lo_, box_hi_;  // the box gather() last covered
  int alive_ = 0;
  int fronts_3d_ = 0;
  std::vector<int> near_edges_, near_nodes_;
};

}  // namespace

long long front_step_budget(double expected_triangles, int boundary_nodes) {
  const double n = boundary_nodes;
  // With no estimate (a face without background triangles) a disc bounded by
  // n nodes holds about n^2 / 5 triangles.
  const double expected = expected_triangles > 0 ? expected_triangles : 0.2 * n * n;
  return static_cast<long long>(std::min(4.0 * expected + 10.0 * n + 1000.0, 4e9));
}

FrontResult advancing_front(FaceMesh& fm, FaceSurface& fs, int strategy, long long max_steps, bool lenient) {
  Front front(fm, fs, std::clamp(strategy, 0, kStrategyCount - 1), max_steps, lenient);
  return front.run();
}

}  // namespace sizemesh
