#include "mesher/ops/collapse.h"

#include <algorithm>
#include <iterator>
#include <utility>

#include "core/predicates.h"

namespace sizemesh {
namespace ops {
namespace {



// The nodes joined to v by an edge, sorted.
std::vector<int> neighbours_of(const FaceMesh& fm, const Balls& balls, int v) {
  std::vector<int> n;
  for (int e = balls.start[v]; e < balls.start[v + 1]; ++e)
    for (int w : fm.tris[balls.tri_of[e]])
      if (w != v) n.push_back(w);
  std::sort(n.begin(), n.end());
  n.erase(std::unique(n.begin(), n.end()), n.end());
  return n;
}

}  // namespace

CollapseCheck check_collapse(const FaceMesh& fm, const FaceSurface& fs, const Balls& balls,
                             const std::vector<char>& locked, int t) {
  const auto tr = fm.tris[t];
  int k = 0;  // shortest side (tr[k], tr[k + 1])
  for (int j = 1; j < 3; ++j)
    if ((fm.position(tr[j]) - fm.position(tr[(j + 1) % 3])).squaredNorm() <
        (fm.position(tr[k]) - fm.position(tr[(k + 1) % 3])).squaredNorm())
      k = j;
  const int a = tr[k], b = tr[(k + 1) % 3];
  if (locked[a] || locked[b]) return {};
  // Try removing each inner end onto the other; keep the better result.
  double best_angle = -1;
  int best_r = -1;
  for (const auto& [r, keep] : {std::pair{a, b}, std::pair{b, a}}) {
    if (fm.boundary(r) || fm.pole[r]) continue;
    // Link condition: common neighbours are exactly the corners opposite the edge.
    const std::vector<int> nr = neighbours_of(fm, balls, r), nk = neighbours_of(fm, balls, keep);
    std::vector<int> common;
    std::set_intersection(nr.begin(), nr.end(), nk.begin(), nk.end(), std::back_inserter(common));
    int opposite = 0;
    double before = 180, after = 180;
    bool valid = true;
    for (int e = balls.start[r]; e < balls.start[r + 1] && valid; ++e) {
      const auto& q = fm.tris[balls.tri_of[e]];
      before = std::min(before, final_min_angle(fm, q));
      if (q[0] == keep || q[1] == keep || q[2] == keep) {
        ++opposite;
        continue;
      }
      std::array<int, 3> moved = q;
      for (int& v : moved)
        if (v == r) v = keep;
      if (fm.pole_triangle(moved)) {
        valid = orient(fm.uv[moved[0]], fm.uv[moved[1]], fm.uv[moved[2]]) > 0;
        continue;
      }
      valid = shape(fm, fs, moved) >= 0;
      after = std::min(after, final_min_angle(fm, moved));
    }
    if (!valid || opposite != 2 || static_cast<int>(common.size()) != 2 || !(after > before)) continue;
    if (after > best_angle) {
      best_angle = after;
      best_r = r;
    }
  }
  if (best_r < 0) return {};
  return {best_r, best_r == a ? b : a};
}

void apply_collapse(FaceMesh& fm, const Balls& balls, const CollapseCheck& c, std::vector<char>& dead,
                    std::vector<char>& locked, std::vector<char>& removed) {
  const int r = c.r, keep = c.keep;
  for (int e = balls.start[r]; e < balls.start[r + 1]; ++e) {
    const int q = balls.tri_of[e];
    auto& Q = fm.tris[q];
    if (Q[0] == keep || Q[1] == keep || Q[2] == keep) {
      dead[q] = 1;
      continue;
    }
    for (int& v : Q)
      if (v == r) v = keep;
  }
  removed[r] = 1;
  for (int v : neighbours_of(fm, balls, r)) locked[v] = 1;
  for (int v : neighbours_of(fm, balls, keep)) locked[v] = 1;
  locked[r] = locked[keep] = 1;
}

}  // namespace ops

// Collapses of the short edge of thin triangles (smallest angle under 12
// degrees): a needle whose short side joins an inner node to another node
// (a sliver the front left between two close nodes) loses that inner node,
// moved onto the other end. Kept only if every triangle of the removed
// node's ball stays valid, the link condition holds (the two ends share no
// neighbour but the corners opposite the edge, so no triangle is doubled),
// and the smallest angle of the ball grows. One collapse per neighbourhood;
// the removed nodes are dropped from fm afterwards.
int collapse_thin_triangles(FaceMesh& fm, const FaceSurface& fs) {
  const ops::Balls balls(fm);
  const int nt = static_cast<int>(fm.tris.size());
  std::vector<char> dead(nt, 0), locked(fm.num_nodes(), 0), removed(fm.num_nodes(), 0);
  int collapsed = 0;
  for (int t = 0; t < nt; ++t) {
    const auto& tr = fm.tris[t];
    if (dead[t] || fm.pole_triangle(tr) || !(ops::final_min_angle(fm, tr) < kSliverDeg)) continue;
    const ops::CollapseCheck c = ops::check_collapse(fm, fs, balls, locked, t);
    if (!c.ok()) continue;
    ops::apply_collapse(fm, balls, c, dead, locked, removed);
    ++collapsed;
  }
  if (collapsed == 0) return 0;
  std::vector<std::array<int, 3>> tris;
  tris.reserve(fm.tris.size());
  for (int t = 0; t < nt; ++t)
    if (!dead[t]) tris.push_back(fm.tris[t]);
  fm.tris = std::move(tris);
  fm.drop_nodes(removed);
  return collapsed;
}

}  // namespace sizemesh
