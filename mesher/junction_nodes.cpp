// Coincident nodes merged along the junction (merge_coincident), open edges counted, the junction measured.
#include "mesher/junction_nodes.h"

#include <map>
#include <set>
#include <unordered_map>

#include "background/background_mesh.h"

namespace sizemesh::cut_faces_detail {

size_t open_edges(const SurfaceMesh& s) {
  std::unordered_map<uint64_t, int> uses;
  for (const auto& t : s.tris)
    for (int k = 0; k < 3; ++k) ++uses[edge_key(t[k], t[(k + 1) % 3])];
  size_t n = 0;
  for (const auto& [e, u] : uses) n += u != 2;
  return n;
}

bool merge_coincident(SurfaceMesh& s, std::vector<std::array<int, 2>>& junction, double tol) {
  std::vector<int> to(s.xyz.size());
  for (size_t i = 0; i < to.size(); ++i) to[i] = static_cast<int>(i);
  auto find = [&](int i) {
    while (to[i] != i) i = to[i] = to[to[i]];
    return i;
  };
  bool any = false;
  for (const auto& t : s.tris)
    for (int k = 0; k < 3; ++k) {
      int a = t[k], b = t[(k + 1) % 3];
      if ((s.xyz[a] - s.xyz[b]).norm() > tol) continue;
      if (s.node_dim[b] < s.node_dim[a]) std::swap(a, b);  // the node on a B-rep point or curve stays
      const int ra = find(a), rb = find(b);
      if (ra == rb) continue;
      to[rb] = ra;
      any = true;
    }
  if (!any) return false;
  SurfaceMesh m = s;
  m.tris.clear(), m.tri_face.clear(), m.tri_uv.clear();
  for (size_t t = 0; t < s.tris.size(); ++t) {
    std::array<int, 3> tr{find(s.tris[t][0]), find(s.tris[t][1]), find(s.tris[t][2])};
    if (tr[0] == tr[1] || tr[1] == tr[2] || tr[0] == tr[2]) continue;
    m.tris.push_back(tr);
    m.tri_face.push_back(s.tri_face[t]);
    m.tri_uv.push_back(s.tri_uv[t]);
  }
  if (open_edges(m) > open_edges(s)) return false;
  s = std::move(m);
  std::vector<std::array<int, 2>> moved;
  for (const auto& [a, b] : junction)
    if (find(a) != find(b)) moved.push_back({find(a), find(b)});
  junction = std::move(moved);
  return true;
}

void measure_junction(const SurfaceMesh& s, const Geometry& g, MeshUnionResult& u, double off) {
  std::map<int, std::map<int, Vec2>> faces_of;  // junction node -> face -> uv there
  std::set<int> nodes;
  for (const auto& [a, b] : u.junction) nodes.insert(a), nodes.insert(b);
  for (size_t t = 0; t < s.tris.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (nodes.count(s.tris[t][k])) faces_of[s.tris[t][k]].emplace(s.tri_face[t], s.tri_uv[t][k]);
  u.junction_nodes = static_cast<int>(nodes.size());
  u.max_junction_gap = 0;
  u.junction_nodes_off = 0;
  u.junction_nodes_unprojected = 0;
  for (const auto& [n, faces] : faces_of) count_junction_node(u, g, s.xyz[n], {faces.begin(), faces.end()}, off);
}

}  // namespace sizemesh::cut_faces_detail
