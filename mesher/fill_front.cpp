#include "mesher/fill_front.h"

#include <unordered_map>
#include <unordered_set>

#include "background/background_mesh.h"

#include "core/predicates.h"

namespace sizemesh {
namespace {

// The open edges chained into closed loops; false when a node starts or ends
// more than one edge (a loop touching itself) or a chain does not close.
bool chain_loops(const std::vector<std::array<int, 2>>& edges, std::vector<std::vector<int>>& loops) {
  std::unordered_map<int, int> next, incoming;
  for (const auto& e : edges) {
    if (!next.emplace(e[0], e[1]).second) return false;
    if (++incoming[e[1]] > 1) return false;
  }
  std::unordered_map<int, bool> used;
  for (const auto& e : edges) {
    if (used[e[0]]) continue;
    std::vector<int> loop;
    int k = e[0];
    while (!used[k]) {
      used[k] = true;
      loop.push_back(k);
      auto it = next.find(k);
      if (it == next.end()) return false;
      k = it->second;
    }
    if (k != e[0]) return false;
    loops.push_back(std::move(loop));
  }
  return true;
}

class EarClipper {
 public:
  EarClipper(const FaceMesh& fm, const FaceSurface& fs, EarTest test) : fm_(fm), fs_(fs), test_(test) {
    for (const auto& t : fm.tris)
      for (int k = 0; k < 3; ++k) edges_.insert(key(t[k], t[(k + 1) % 3]));
  }

  // Triangulates one loop into tris; false when no valid ear is left.
  bool clip(std::vector<int> loop, std::vector<std::array<int, 3>>& tris) {
    double area = 0;
    for (size_t i = 0; i < loop.size(); ++i)
      area += orient(Vec2(0, 0), fm_.uv[loop[i]], fm_.uv[loop[(i + 1) % loop.size()]]);
    if (!(area > 0)) return false;  // a hole's loop, or a degenerate one
    while (loop.size() >= 3) {
      const int n = static_cast<int>(loop.size());
      int best = -1;
      double best_q = -1;
      for (int i = 0; i < n; ++i) {
        const double q = ear_quality(loop, i);
        if (q > best_q) {
          best_q = q;
          best = i;
        }
      }
      if (best < 0) return false;
      tris.push_back({loop[(best + n - 1) % n], loop[best], loop[(best + 1) % n]});
      edges_.insert(key(loop[(best + n - 1) % n], loop[(best + 1) % n]));
      loop.erase(loop.begin() + best);
      if (loop.size() == 2) break;
    }
    return true;
  }

 private:
  // Shape quality in space of the ear at loop[i], or -1 when it is not valid.
  double ear_quality(const std::vector<int>& loop, int i) const {
    const int n = static_cast<int>(loop.size());
    const int a = loop[(i + n - 1) % n], b = loop[i], c = loop[(i + 1) % n];
    const Vec2 &ua = fm_.uv[a], &ub = fm_.uv[b], &uc = fm_.uv[c];
    const double o = orient(ua, ub, uc);
    const double scale = (ub - ua).norm() * (uc - ub).norm();
    if (!(o > 1e-12 * scale)) return -1;
    // The new edge c-a must not join two uv images of one node (a seam), nor
    // repeat an edge the mesh has in space (it would end non-manifold).
    if (n > 3 && !(fm_.pole[a] && fm_.pole[c]) && (identity(a) == identity(c) || edges_.count(key(a, c))))
      return -1;
    for (int k : loop) {
      if (k == a || k == b || k == c) continue;
      const Vec2& p = fm_.uv[k];
      if (orient(ua, ub, p) >= 0 && orient(ub, uc, p) >= 0 && orient(uc, ua, p) >= 0) return -1;
    }
    if (test_ == EarTest::kFacing && turned(ua, ub, uc, fm_.s[a], fm_.s[b], fm_.s[c])) return -1;
    if (test_ == EarTest::kCentroid &&
        fs_.turned_at_centroid(ua, ub, uc, (fm_.s[b].p - fm_.s[a].p).cross(fm_.s[c].p - fm_.s[a].p)))
      return -1;
    return triangle_quality(fm_.s[a].p, fm_.s[b].p, fm_.s[c].p);
  }

  // Against the surface normal at a corner or at the uv centroid (the
  // quality report's inverted triangle).
  bool turned(const Vec2& ua, const Vec2& ub, const Vec2& uc, const SurfaceSample& sa, const SurfaceSample& sb,
              const SurfaceSample& sc) const {
    const Vec3 nt = (sb.p - sa.p).cross(sc.p - sa.p);
    for (const SurfaceSample* s : {&sa, &sb, &sc})
      if (s->n.squaredNorm() > 0 && !(nt.dot(s->n) > 0)) return true;
    return fs_.turned_at_centroid(ua, ub, uc, nt);
  }

  // A node's identity in space: its shared id on the boundary (seam copies agree), else its own.
  int identity(int k) const { return fm_.global[k] >= 0 ? fm_.global[k] : (1 << 30) + k; }
  uint64_t key(int a, int b) const { return edge_key(identity(a), identity(b)); }

  const FaceMesh& fm_;
  const FaceSurface& fs_;
  EarTest test_;
  std::unordered_set<uint64_t> edges_;  // mesh edges in space (identity pairs)
};

}  // namespace

bool fill_front(FaceMesh& fm, const FaceSurface& fs, const std::vector<std::array<int, 2>>& open_edges,
                EarTest test, int max_edges) {
  if (open_edges.empty() || static_cast<int>(open_edges.size()) > max_edges) return false;
  std::vector<std::vector<int>> loops;
  if (!chain_loops(open_edges, loops)) return false;
  EarClipper clipper(fm, fs, test);
  std::vector<std::array<int, 3>> tris;
  for (const auto& loop : loops)
    if (!clipper.clip(loop, tris)) return false;
  fm.tris.insert(fm.tris.end(), tris.begin(), tris.end());
  return true;
}

}  // namespace sizemesh
