// Faces that mesh the same strip twice: back-to-back triangle pairs dropped, shared inner edges flipped.
#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include "mesher/mesh_surface.h"

namespace sizemesh {

void drop_back_to_back(SurfaceMesh& m) {
  // Triangles by their sorted nodes, then index: groups of equal keys in key
  // order, each group in triangle order.
  using Keyed = std::pair<std::array<int, 3>, int>;
  std::vector<Keyed> keyed(m.tris.size());
  for (size_t t = 0; t < m.tris.size(); ++t) {
    keyed[t] = {m.tris[t], static_cast<int>(t)};
    std::sort(keyed[t].first.begin(), keyed[t].first.end());
  }
  std::sort(keyed.begin(), keyed.end());
  // Opposite orientation: b's cyclic order is a's reversed.
  auto opposite = [&](int a, int b) {
    const auto &x = m.tris[a], &y = m.tris[b];
    for (int k = 0; k < 3; ++k)
      if (y[k] == x[0]) return y[(k + 1) % 3] == x[2];
    return false;
  };
  std::vector<char> drop(m.tris.size(), 0);
  for (size_t lo = 0, hi = 0; lo < keyed.size(); lo = hi) {
    while (hi < keyed.size() && keyed[hi].first == keyed[lo].first) ++hi;
    for (size_t i = lo; i < hi; ++i)
      for (size_t j = i + 1; j < hi && !drop[keyed[i].second]; ++j)
        if (!drop[keyed[j].second] && opposite(keyed[i].second, keyed[j].second))
          drop[keyed[i].second] = drop[keyed[j].second] = 1;
  }
  size_t kept = 0;
  for (size_t t = 0; t < m.tris.size(); ++t) {
    if (drop[t]) continue;
    m.tris[kept] = m.tris[t];
    m.tri_face[kept] = m.tri_face[t];
    m.tri_uv[kept] = m.tri_uv[t];
    ++kept;
  }
  m.stats.back_to_back_dropped = static_cast<int>(m.tris.size() - kept);
  m.tris.resize(kept);
  m.tri_face.resize(kept);
  m.tri_uv.resize(kept);
}

void flip_shared_inner_edges(SurfaceMesh& m) {
  // Every side as (edge with a < b, triangle), sorted: the triangles using an
  // edge are a run, in triangle order. The edges are those of the mesh as it
  // came; a flip below does not add its new edge.
  using Edge = std::pair<int, int>;
  std::vector<std::pair<Edge, int>> sides;
  sides.reserve(3 * m.tris.size());
  for (size_t t = 0; t < m.tris.size(); ++t)
    for (int k = 0; k < 3; ++k)
      sides.push_back({std::minmax(m.tris[t][k], m.tris[t][(k + 1) % 3]), static_cast<int>(t)});
  std::sort(sides.begin(), sides.end());
  const auto used = [&](const Edge& e) {
    const auto it = std::lower_bound(sides.begin(), sides.end(), std::pair<Edge, int>(e, -1));
    return it != sides.end() && it->first == e;
  };
  auto normal = [&](const std::array<int, 3>& t) {
    return (m.xyz[t[1]] - m.xyz[t[0]]).cross(m.xyz[t[2]] - m.xyz[t[0]]);
  };
  int flipped = 0;
  for (size_t lo = 0, hi = 0; lo < sides.size(); lo = hi) {
    while (hi < sides.size() && sides[hi].first == sides[lo].first) ++hi;
    if (hi - lo != 4) continue;
    const Edge e = sides[lo].first;
    // Two faces, two triangles each: flip the edge inside the first face
    // whose quad allows it.
    std::map<int, std::vector<int>> by_face;
    for (size_t i = lo; i < hi; ++i) by_face[m.tri_face[sides[i].second]].push_back(sides[i].second);
    if (by_face.size() != 2) continue;
    for (auto& [f, pair] : by_face) {
      if (pair.size() != 2) break;
      const int t1 = pair[0], t2 = pair[1];
      // t1 = (a, b, c) with a -> b along the edge; t2 holds b -> a and d.
      int k1 = 0;
      while (k1 < 3 && Edge(std::minmax(m.tris[t1][k1], m.tris[t1][(k1 + 1) % 3])) != e) ++k1;
      if (k1 == 3) break;  // t1 was flipped across another of its edges
      const int a = m.tris[t1][k1], b = m.tris[t1][(k1 + 1) % 3], c = m.tris[t1][(k1 + 2) % 3];
      int k2 = 0;
      while (k2 < 3 && m.tris[t2][k2] != b) ++k2;
      if (k2 == 3 || m.tris[t2][(k2 + 1) % 3] != a) break;  // not opposite: leave it
      const int d = m.tris[t2][(k2 + 2) % 3];
      if (c == d || used(std::minmax(c, d))) break;
      auto uv_of = [&](int t, int n) {
        for (int k = 0; k < 3; ++k)
          if (m.tris[t][k] == n) return m.tri_uv[t][k];
        return Vec2(0, 0);
      };
      const std::array<int, 3> n1 = {a, d, c}, n2 = {d, b, c};
      const Vec3 before = normal(m.tris[t1]) + normal(m.tris[t2]);
      if (!(normal(n1).dot(before) > 0 && normal(n2).dot(before) > 0)) continue;
      const std::array<Vec2, 3> uv1 = {uv_of(t1, a), uv_of(t2, d), uv_of(t1, c)};
      const std::array<Vec2, 3> uv2 = {uv_of(t2, d), uv_of(t1, b), uv_of(t1, c)};
      m.tris[t1] = n1, m.tri_uv[t1] = uv1;
      m.tris[t2] = n2, m.tri_uv[t2] = uv2;
      ++flipped;
      break;
    }
  }
  m.stats.shared_edges_flipped = flipped;
}

}  // namespace sizemesh
