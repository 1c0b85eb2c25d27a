// Thin triangles along a union's junction removed: which ones, the best operation for each, the mesh renumbered.
#include "mesher/junction_slivers.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <set>

#include "core/predicates.h"
#include "mesher/self_intersection.h"
#include "mesher/sliver_cleaner.h"

namespace sizemesh {
namespace junction_slivers_detail {

bool Cleaner::improve(int t, std::vector<int>& made, JunctionSliverResult& count) {
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

}  // namespace junction_slivers_detail

using namespace junction_slivers_detail;  // Cleaner

JunctionSliverResult remove_junction_slivers(SurfaceMesh& s, const Geometry& g, const SizeField& h,
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
