#include "mesher/junction_slivers.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <set>

#include "geometry/predicates.h"
#include "mesher/self_intersection.h"

namespace sizemesh {

namespace {

constexpr double kLeanCos = 0.70710678118654752;  // cos 45 deg: a triangle's largest lean off its surface

// The smallest angle of a set of triangles, and how many are under 12 degrees.
struct Shape {
  int thin = 0;
  double min = 180;
  void add(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double m = min_angle_deg(a, b, c);
    thin += m < kSliverDeg;
    min = std::min(min, m);
  }
  // Better than `old`: fewer thin triangles, none far thinner than the
  // thinnest before (the strip's next ones go in later steps), or as many
  // and a larger smallest angle.
  bool better_than(const Shape& old) const {
    return (thin < old.thin && min > 0.25 * old.min) || (thin <= old.thin && min > old.min + 1e-9);
  }
};

class Cleaner {
 public:
  Cleaner(SurfaceMesh& s, const Geometry& g, const SizeFunction& h)
      : s_(s), g_(g), h_(h), node_tris_(s.xyz.size()), dead_(s.tris.size(), 0), merged_into_(s.xyz.size(), -1) {
    for (size_t t = 0; t < s.tris.size(); ++t)
      for (int n : s.tris[t]) node_tris_[n].push_back(static_cast<int>(t));
  }

  double min_angle(int t) const {
    const auto& tr = s_.tris[t];
    return min_angle_deg(s_.xyz[tr[0]], s_.xyz[tr[1]], s_.xyz[tr[2]]);
  }
  bool dead(int t) const { return dead_[t] != 0; }
  const std::vector<int>& merged_into() const { return merged_into_; }
  const std::vector<char>& dead_tris() const { return dead_; }

  std::vector<int> alive(int n) const {
    std::vector<int> out;
    for (int t : node_tris_[n])
      if (!dead_[t]) out.push_back(t);
    return out;
  }

  // The best operation that removes thin triangle t, applied; the triangles
  // it made are appended to `made`. False when none improves on t's
  // neighbourhood.
  bool improve(int t, std::vector<int>& made, JunctionSliverResult& count) {
    enum Kind { kNone, kCollapse, kFlip, kPinch };
    Kind best = kNone;
    Shape best_shape;
    int best_from = -1, best_to = -1;
    int gain_best = 0;
    auto consider = [&](Kind kind, const Shape& before, const Shape& after, int from, int to) {
      if (!after.better_than(before)) return;
      const int gain = before.thin - after.thin;
      if (best != kNone && (gain < gain_best || (gain == gain_best && after.min <= best_shape.min))) return;
      best = kind, best_shape = after, best_from = from, best_to = to, gain_best = gain;
    };
    const auto tr = s_.tris[t];
    // Nodes of different curves merge when closer than tan(12 deg) of the
    // size wanted or of this triangle's longest edge.
    double reach = 0;
    for (int k = 0; k < 3; ++k) reach = std::max(reach, (s_.xyz[tr[(k + 1) % 3]] - s_.xyz[tr[k]]).norm());
    reach *= kSliverTan;
    for (int k = 0; k < 3; ++k)
      for (int dir = 0; dir < 2; ++dir) {
        const int b = tr[(k + dir) % 3], a = tr[(k + 1 - dir) % 3];
        Shape before, after;
        if (collapse(b, a, reach, false, before, after)) consider(kCollapse, before, after, b, a);
      }
    {
      Shape before, after;
      if (flip(t, false, before, after)) consider(kFlip, before, after, t, -1);
    }
    {
      Shape before, after;
      if (pinch(t, false, before, after)) consider(kPinch, before, after, t, -1);
    }
    if (best == kNone) return false;
    Shape before, after;
    if (best == kCollapse) {
      collapse(best_from, best_to, HUGE_VAL, true, before, after);
      for (int x : alive(best_to)) made.push_back(x);
      ++count.collapsed;
    } else if (best == kFlip) {
      flip(best_from, true, before, after);
      made.push_back(best_from);
      made.push_back(flipped_other_);
      ++count.flipped;
    } else {
      pinch(best_from, true, before, after);
      made.push_back(flipped_other_);
      made.push_back(static_cast<int>(s_.tris.size()) - 1);
      ++count.pinched;
    }
    return true;
  }

 private:
  int corner(int t, int n) const {
    return static_cast<int>(std::find(s_.tris[t].begin(), s_.tris[t].end(), n) - s_.tris[t].begin());
  }
  std::vector<int> faces(int n) const {
    std::vector<int> f;
    for (int t : node_tris_[n])
      if (!dead_[t]) f.push_back(s_.tri_face[t]);
    std::sort(f.begin(), f.end());
    f.erase(std::unique(f.begin(), f.end()), f.end());
    return f;
  }
  std::vector<int> neighbours(int n) const {
    std::vector<int> out;
    for (int t : node_tris_[n])
      if (!dead_[t])
        for (int m : s_.tris[t])
          if (m != n) out.push_back(m);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  // The cosine of the angle between a triangle's normal and its face's
  // surface normal at its centroid; 1 where the surface has none (a pole).
  double lean(int f, const std::array<Vec3, 3>& x, const std::array<Vec2, 3>& uv) const {
    const Vec3 n = (x[1] - x[0]).cross(x[2] - x[0]);
    const double ln = n.norm();
    if (!(ln > 0)) return -1;
    SurfaceD1 d;
    try {
      d = g_.eval_face(f, (uv[0] + uv[1] + uv[2]) / 3.0);
    } catch (const EvaluationError&) {
      return -1;
    }
    Vec3 ns = d.du.cross(d.dv);
    if (g_.face_reversed(f)) ns = -ns;
    const double ls = ns.norm();
    if (!(ls > 0) || !std::isfinite(ls)) return 1;
    return n.dot(ns) / (ln * ls);
  }
  double lean(int t) const {
    const auto& tr = s_.tris[t];
    return lean(s_.tri_face[t], {s_.xyz[tr[0]], s_.xyz[tr[1]], s_.xyz[tr[2]]}, s_.tri_uv[t]);
  }
  // Node n's uv in face f near `near`: from a triangle of f at n, else by
  // projecting n onto f.
  bool uv_in(int n, int f, const Vec2& near, Vec2& out) const {
    for (int t : node_tris_[n])
      if (!dead_[t] && s_.tri_face[t] == f) {
        out = unwrap_uv(g_, f, s_.tri_uv[t][corner(t, n)], near);
        return true;
      }
    out = near;
    if (!g_.project_to_face(f, s_.xyz[n], out)) return false;
    out = unwrap_uv(g_, f, out, near);
    return true;
  }
  // True when a triangle of face f on nodes n, under 12 degrees, is an ear
  // of its face's boundary (two of its edges on it, `face_across` giving
  // another face or none) at a corner that is not its smallest angle: no
  // sharp corner of the face forces it.
  bool thin_ear(int f, const std::array<int, 3>& n, const std::function<int(int, int)>& face_across) const {
    const auto ang = corner_angles_deg(s_.xyz[n[0]], s_.xyz[n[1]], s_.xyz[n[2]]);
    const double least = std::min({ang[0], ang[1], ang[2]});
    if (!(least < kSliverDeg)) return false;
    for (int k = 0; k < 3; ++k)
      if (ang[k] > least && face_across(n[k], n[(k + 1) % 3]) != f && face_across(n[(k + 2) % 3], n[k]) != f)
        return true;
    return false;
  }

  // The size wanted at node n (the finest of its faces').
  double size_at(int n) const {
    double best = HUGE_VAL;
    for (int t : node_tris_[n]) {
      if (dead_[t]) continue;
      int hint = -1;
      best = std::min(best, h_.at(s_.tri_face[t], s_.tri_uv[t][corner(t, n)], hint));
    }
    return best;
  }

  // Node b merged into its neighbour a (a stays where it is): allowed when a
  // is on every face b is on (and on b's curve), or when they are closer than
  // `reach` or tan(12 deg) of the size wanted there; never a B-rep point moved, never
  // an edge used more than twice after it.
  bool collapse(int b, int a, double reach, bool apply, Shape& before, Shape& after) {
    if (s_.node_dim[b] == 0) return false;
    const std::vector<int> fb = faces(b), fa = faces(a);
    bool within = std::includes(fa.begin(), fa.end(), fb.begin(), fb.end());
    if (s_.node_dim[b] == 1 && s_.node_dim[a] == 1 && s_.node_entity[a] != s_.node_entity[b]) within = false;
    if (!within && !((s_.xyz[a] - s_.xyz[b]).norm() < std::max(reach, kSliverTan * size_at(b)))) return false;
    const std::vector<int> tb = alive(b);
    std::vector<int> shared, opposite;
    for (int t : tb)
      if (corner(t, a) < 3) {
        shared.push_back(t);
        for (int n : s_.tris[t])
          if (n != a && n != b) opposite.push_back(n);
      }
    if (shared.size() != 2) return false;
    std::sort(opposite.begin(), opposite.end());
    const std::vector<int> na = neighbours(a), nb = neighbours(b);
    std::vector<int> common;
    std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
    if (common != opposite) return false;
    double limit = kLeanCos;
    for (int t : tb) {
      const auto& tr = s_.tris[t];
      before.add(s_.xyz[tr[0]], s_.xyz[tr[1]], s_.xyz[tr[2]]);
      limit = std::min(limit, lean(t));
    }
    limit = std::max(limit, 0.0);
    std::vector<std::pair<int, Vec2>> moved;  // triangle, a's uv in it
    for (int t : tb) {
      if (corner(t, a) < 3) continue;
      const int k = corner(t, b), f = s_.tri_face[t];
      Vec2 uv;
      if (!uv_in(a, f, s_.tri_uv[t][k], uv)) return false;
      std::array<Vec3, 3> x{s_.xyz[s_.tris[t][0]], s_.xyz[s_.tris[t][1]], s_.xyz[s_.tris[t][2]]};
      std::array<Vec2, 3> w = s_.tri_uv[t];
      x[k] = s_.xyz[a];
      w[k] = uv;
      if (!(lean(f, x, w) > limit)) return false;
      after.add(x[0], x[1], x[2]);
      moved.emplace_back(t, uv);
    }
    // The face across edge (u, v) once b is merged into a.
    auto face_across = [&](int self, int u, int v) {
      std::vector<int> around = alive(u);
      if (u == a) around.insert(around.end(), tb.begin(), tb.end());
      for (int t : around) {
        if (t == self || std::find(shared.begin(), shared.end(), t) != shared.end()) continue;
        auto c = s_.tris[t];
        for (int& n : c) n = n == b ? a : n;
        if (std::find(c.begin(), c.end(), v) != c.end()) return s_.tri_face[t];
      }
      return -1;
    };
    for (const auto& [t, uv] : moved) {
      auto c = s_.tris[t];
      for (int& n : c) n = n == b ? a : n;
      if (thin_ear(s_.tri_face[t], c, [&](int u, int v) { return face_across(t, u, v); })) return false;
    }
    if (!apply) return true;
    for (int t : shared) dead_[t] = 1;
    for (const auto& [t, uv] : moved) {
      const int k = corner(t, b);
      s_.tris[t][k] = a;
      s_.tri_uv[t][k] = uv;
      node_tris_[a].push_back(t);
    }
    node_tris_[b].clear();
    merged_into_[b] = a;
    return true;
  }

  // Triangle t = (r, p, q) with its largest angle at r (corner kr), and the
  // one triangle t2 = (q, p, o) across (p, q), o not yet joined to r: what a
  // flip or a pinch of t changes. False when (p, q) is not an inner edge of
  // the mesh or r and o are joined already.
  struct Across {
    int r, p, q, kr, t2, o;
    double angle;  // at r, degrees
  };
  bool across_largest(int t, Across& x) const {
    const auto tr = s_.tris[t];
    const auto ang = corner_angles_deg(s_.xyz[tr[0]], s_.xyz[tr[1]], s_.xyz[tr[2]]);
    x.kr = static_cast<int>(std::max_element(ang.begin(), ang.end()) - ang.begin());
    x.angle = ang[x.kr];
    x.r = tr[x.kr], x.p = tr[(x.kr + 1) % 3], x.q = tr[(x.kr + 2) % 3];
    int across = 0;
    x.t2 = -1;
    for (int u : node_tris_[x.p])
      if (u != t && !dead_[u] && corner(u, x.q) < 3) x.t2 = u, ++across;
    if (across != 1) return false;
    x.o = -1;
    for (int n : s_.tris[x.t2])
      if (n != x.p && n != x.q) x.o = n;
    const std::vector<int> nr = neighbours(x.r);
    return x.o >= 0 && x.o != x.r && !std::binary_search(nr.begin(), nr.end(), x.o);
  }
  // Triangle x no longer at node n.
  void drop_tri(int n, int x) {
    auto& v = node_tris_[n];
    v.erase(std::remove(v.begin(), v.end(), x), v.end());
  }

  // The edge opposite t's largest angle flipped, when the triangle across it
  // is of the same face.
  bool flip(int t, bool apply, Shape& before, Shape& after) {
    Across x;
    if (!across_largest(t, x) || s_.tri_face[x.t2] != s_.tri_face[t]) return false;
    const int r = x.r, p = x.p, q = x.q, kr = x.kr, t2 = x.t2, o = x.o, f = s_.tri_face[t];
    const Vec2 ur = s_.tri_uv[t][kr], up = s_.tri_uv[t][(kr + 1) % 3], uq = s_.tri_uv[t][(kr + 2) % 3];
    const Vec2 uo = s_.tri_uv[t2][corner(t2, o)] + (up - s_.tri_uv[t2][corner(t2, p)]);
    before.add(s_.xyz[r], s_.xyz[p], s_.xyz[q]);
    before.add(s_.xyz[q], s_.xyz[p], s_.xyz[o]);
    const double limit = std::max(0.0, std::min({kLeanCos, lean(t), lean(t2)}));
    const std::array<Vec3, 3> x1{s_.xyz[r], s_.xyz[p], s_.xyz[o]}, x2{s_.xyz[r], s_.xyz[o], s_.xyz[q]};
    const std::array<Vec2, 3> w1{ur, up, uo}, w2{ur, uo, uq};
    if (!(lean(f, x1, w1) > limit) || !(lean(f, x2, w2) > limit)) return false;
    // The faces across the four outer edges stay; the new one is inside f.
    auto face_across = [&](int u, int v) {
      if ((u == r && v == o) || (u == o && v == r)) return f;
      const int skip = (u == r || v == r) ? t : t2;
      for (int x : node_tris_[u])
        if (x != skip && x != (skip == t ? t2 : t) && !dead_[x] && corner(x, v) < 3) return s_.tri_face[x];
      return -1;
    };
    if (thin_ear(f, {r, p, o}, face_across) || thin_ear(f, {r, o, q}, face_across)) return false;
    after.add(x1[0], x1[1], x1[2]);
    after.add(x2[0], x2[1], x2[2]);
    if (!apply) return true;
    s_.tris[t] = {r, p, o};
    s_.tri_uv[t] = w1;
    s_.tris[t2] = {r, o, q};
    s_.tri_uv[t2] = w2;
    node_tris_[r].push_back(t2);
    node_tris_[o].push_back(t);
    drop_tri(p, t2);
    drop_tri(q, t);
    flipped_other_ = t2;
    return true;
  }

  // Thin triangle t = (r, p, q) with its largest angle (over 90 degrees)
  // at r, a node of a curve or junction, where the triangle across (p, q) is
  // of another face: r lies within a sliver's height of that face boundary
  // (a junction touching a curve), and is put on it. t goes, the triangle
  // across is split at r in two.
  bool pinch(int t, bool apply, Shape& before, Shape& after) {
    Across x;
    if (!across_largest(t, x) || !(x.angle > 90) || faces(x.r).size() < 2 || s_.tri_face[x.t2] == s_.tri_face[t])
      return false;
    const int r = x.r, p = x.p, q = x.q, t2 = x.t2, o = x.o, f2 = s_.tri_face[t2];
    const Vec2 up = s_.tri_uv[t2][corner(t2, p)], uq = s_.tri_uv[t2][corner(t2, q)], uo = s_.tri_uv[t2][corner(t2, o)];
    Vec2 ur;
    if (!uv_in(r, f2, 0.5 * (up + uq), ur)) return false;
    before.add(s_.xyz[r], s_.xyz[p], s_.xyz[q]);
    before.add(s_.xyz[q], s_.xyz[p], s_.xyz[o]);
    const double limit = std::max(0.0, std::min({kLeanCos, lean(t2)}));
    const std::array<Vec3, 3> x1{s_.xyz[q], s_.xyz[r], s_.xyz[o]}, x2{s_.xyz[r], s_.xyz[p], s_.xyz[o]};
    const std::array<Vec2, 3> w1{uq, ur, uo}, w2{ur, up, uo};
    if (!(lean(f2, x1, w1) > limit) || !(lean(f2, x2, w2) > limit)) return false;
    // Across (q, r) and (r, p): t's neighbours; across (p, o), (o, q): t2's.
    auto face_across = [&](int u, int v) {
      if ((u == r && v == o) || (u == o && v == r)) return f2;
      for (int x : node_tris_[u])
        if (x != t && x != t2 && !dead_[x] && corner(x, v) < 3) return s_.tri_face[x];
      return -1;
    };
    if (thin_ear(f2, {q, r, o}, face_across) || thin_ear(f2, {r, p, o}, face_across)) return false;
    after.add(x1[0], x1[1], x1[2]);
    after.add(x2[0], x2[1], x2[2]);
    if (!apply) return true;
    dead_[t] = 1;
    s_.tris[t2] = {q, r, o};
    s_.tri_uv[t2] = w1;
    s_.tris.push_back({r, p, o});
    s_.tri_uv.push_back(w2);
    s_.tri_face.push_back(f2);
    dead_.push_back(0);
    const int t3 = static_cast<int>(s_.tris.size()) - 1;
    node_tris_[r].push_back(t2);
    node_tris_[r].push_back(t3);
    node_tris_[p].push_back(t3);
    node_tris_[o].push_back(t3);
    drop_tri(p, t2);
    flipped_other_ = t2;
    return true;
  }

  SurfaceMesh& s_;
  const Geometry& g_;
  const SizeFunction& h_;
  std::vector<std::vector<int>> node_tris_;
  std::vector<char> dead_;
  std::vector<int> merged_into_;
  int flipped_other_ = -1;
};

}  // namespace

JunctionSliverResult remove_junction_slivers(SurfaceMesh& s, const Geometry& g, const SizeFunction& h,
                                             std::vector<std::array<int, 2>>& junction, long long crossing_pairs) {
  JunctionSliverResult out;
  if (junction.empty()) return out;
  // The faces the junction runs along, and the thin triangles at their nodes.
  std::set<int> cut;
  std::vector<char> on_junction(s.xyz.size(), 0), near(s.xyz.size(), 0);
  for (const auto& [a, b] : junction) on_junction[a] = on_junction[b] = 1;
  for (size_t t = 0; t < s.tris.size(); ++t)
    for (int v : s.tris[t])
      if (on_junction[v]) cut.insert(s.tri_face[t]);
  for (size_t t = 0; t < s.tris.size(); ++t)
    if (cut.count(s.tri_face[t]))
      for (int v : s.tris[t]) near[v] = 1;
  std::deque<int> queue;
  for (size_t t = 0; t < s.tris.size(); ++t) {
    const auto& tr = s.tris[t];
    if ((near[tr[0]] || near[tr[1]] || near[tr[2]]) && min_angle_deg(s.xyz[tr[0]], s.xyz[tr[1]], s.xyz[tr[2]]) < kSliverDeg)
      queue.push_back(static_cast<int>(t));
  }
  if (queue.empty()) return out;
  const SurfaceMesh backup = s;
  Cleaner c(s, g, h);
  // Each operation removes a thin triangle or raises the smallest angle
  // around it; a few per triangle bound the work.
  const size_t budget = 8 * queue.size() + 64;
  size_t ops = 0;
  while (!queue.empty() && ops < budget) {
    const int t = queue.front();
    queue.pop_front();
    if (c.dead(t) || !(c.min_angle(t) < kSliverDeg)) continue;
    std::vector<int> made;
    if (!c.improve(t, made, out)) continue;
    ++ops;
    for (int x : made)
      if (!c.dead(x) && c.min_angle(x) < kSliverDeg) queue.push_back(x);
  }
  if (out.collapsed + out.flipped == 0) return out;
  // Unused nodes dropped, the others and the triangles in their order.
  const std::vector<char>& dead = c.dead_tris();
  std::vector<int> id(s.xyz.size(), -1);
  for (size_t t = 0; t < s.tris.size(); ++t)
    if (!dead[t])
      for (int n : s.tris[t]) id[n] = 0;
  SurfaceMesh m;
  m.failures = s.failures;
  m.stats = s.stats;
  for (size_t n = 0; n < s.xyz.size(); ++n)
    if (id[n] == 0) {
      id[n] = static_cast<int>(m.xyz.size());
      m.xyz.push_back(s.xyz[n]);
      m.node_dim.push_back(s.node_dim[n]);
      m.node_entity.push_back(s.node_entity[n]);
    }
  for (size_t t = 0; t < s.tris.size(); ++t)
    if (!dead[t]) {
      m.tris.push_back({id[s.tris[t][0]], id[s.tris[t][1]], id[s.tris[t][2]]});
      m.tri_face.push_back(s.tri_face[t]);
      m.tri_uv.push_back(s.tri_uv[t]);
    }
  auto root = [&](int n) {
    while (c.merged_into()[n] >= 0) n = c.merged_into()[n];
    return id[n];
  };
  std::set<std::pair<int, int>> seen;
  std::vector<std::array<int, 2>> edges;
  for (const auto& [a, b] : junction) {
    const int ra = root(a), rb = root(b);
    if (ra >= 0 && rb >= 0 && ra != rb && seen.insert(std::minmax(ra, rb)).second) edges.push_back({ra, rb});
  }
  if (crossing_pairs < 0) crossing_pairs = find_self_intersections(backup, 0).pairs;
  if (find_self_intersections(m, 0).pairs > crossing_pairs) {
    s = backup;
    return JunctionSliverResult{};
  }
  s = std::move(m);
  junction = std::move(edges);
  return out;
}

}  // namespace sizemesh
