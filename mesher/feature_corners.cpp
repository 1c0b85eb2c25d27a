#include "mesher/feature_corners.h"

#include <algorithm>
#include <unordered_map>

#include "core/mesh_topology.h"
#include "core/predicates.h"

namespace sizemesh {

std::vector<char> at_feature_corners(const SurfaceMesh& m, const std::unordered_set<uint64_t>& kept,
                                     const std::vector<double>& min_angle) {
  std::vector<char> out(m.tris.size(), 0);
  std::vector<int> thin;
  for (size_t t = 0; t < m.tris.size(); ++t)
    if (min_angle[t] < kSliverDeg) thin.push_back(static_cast<int>(t));
  if (thin.empty()) return out;
  std::vector<int> start, ids;
  vertex_triangles(static_cast<int>(m.xyz.size()), m.tris, start, ids);
  auto angle_at = [&](int t, int n) {
    const auto& tr = m.tris[t];
    const auto a = corner_angles_deg(m.xyz[tr[0]], m.xyz[tr[1]], m.xyz[tr[2]]);
    return a[std::find(tr.begin(), tr.end(), n) - tr.begin()];
  };
  // The other triangle at node n across edge (n, o) from t; -1 when none or several.
  auto across = [&](int t, int n, int o) {
    int found = -1;
    for (int i = start[n]; i < start[n + 1]; ++i) {
      const int u = ids[i];
      if (u == t || std::find(m.tris[u].begin(), m.tris[u].end(), o) == m.tris[u].end()) continue;
      if (found >= 0) return -1;
      found = u;
    }
    return found;
  };
  for (int t : thin) {
    const auto& tr = m.tris[t];
    const auto a = corner_angles_deg(m.xyz[tr[0]], m.xyz[tr[1]], m.xyz[tr[2]]);
    const int k = static_cast<int>(std::min_element(a.begin(), a.end()) - a.begin());
    const int n = tr[k];
    // Walk round n both ways from t until a kept edge: the wedge's angle.
    double wedge = a[k];
    bool closed = true;
    for (int side : {1, 2}) {
      int cur = t, o = tr[(k + side) % 3];
      for (int step = 0;; ++step) {
        if (kept.count(edge_key(n, o))) break;
        if (step == 64) {
          closed = false;
          break;
        }
        const int next = across(cur, n, o);
        if (next < 0 || next == t) {
          closed = false;
          break;
        }
        wedge += angle_at(next, n);
        if (wedge >= kSliverDeg) {
          closed = false;
          break;
        }
        const auto& nt = m.tris[next];
        for (int v : nt)
          if (v != n && v != o) {
            o = v;
            break;
          }
        cur = next;
      }
      if (!closed) break;
    }
    out[t] = closed && wedge < kSliverDeg;
  }
  return out;
}

}  // namespace sizemesh
