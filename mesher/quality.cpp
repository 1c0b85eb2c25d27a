#include "mesher/quality.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "mesher/geometry2d.h"

namespace sizemesh {

MeshQuality mesh_quality(const SurfaceMesh& m, const Geometry& g, const SizeFunction& h) {
  MeshQuality q;
  q.triangles = static_cast<int>(m.tris.size());
  q.nodes = static_cast<int>(m.xyz.size());
  q.min_angle.resize(m.tris.size());
  // Directed edge uses: an edge of a closed, consistently oriented mesh is used
  // once each way.
  std::unordered_map<uint64_t, int> directed;
  directed.reserve(m.tris.size() * 3);
  auto code = [](int a, int b) { return (uint64_t(uint32_t(a)) << 32) | uint32_t(b); };
  for (size_t t = 0; t < m.tris.size(); ++t) {
    const auto& tr = m.tris[t];
    const Vec3 &a = m.xyz[tr[0]], &b = m.xyz[tr[1]], &c = m.xyz[tr[2]];
    const double ang = min_angle_deg(a, b, c);
    q.min_angle[t] = ang;
    q.histogram[std::min(9, static_cast<int>(ang / 6.0))]++;
    if (ang < 12) ++q.below_12;
    if (ang < 24) ++q.below_24;
    q.worst_angle = std::min(q.worst_angle, ang);
    const Vec3 n = (b - a).cross(c - a);
    const double l2 = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
    q.area += 0.5 * n.norm();
    if (!(n.norm() > 1e-12 * l2)) ++q.zero_area;
    // Against the surface normal at the uv centroid, oriented as in the shell.
    const int f = m.tri_face[t];
    const Vec2 uvc = (m.tri_uv[t][0] + m.tri_uv[t][1] + m.tri_uv[t][2]) / 3.0;
    const SurfaceD1 s = g.eval_face(f, uvc);
    Vec3 ns = s.du.cross(s.dv);
    if (g.face_reversed(f)) ns = -ns;
    if (ns.norm() > 0 && n.dot(ns) <= 0) ++q.inverted;
    for (int k = 0; k < 3; ++k) {
      const double d = (g.eval_face(f, m.tri_uv[t][k]).p - m.xyz[tr[k]]).norm();
      q.max_node_distance = std::max(q.max_node_distance, d);
      if (m.node_dim[tr[k]] == 2) q.max_inner_node_distance = std::max(q.max_inner_node_distance, d);
      directed[code(tr[k], tr[(k + 1) % 3])]++;
    }
  }
  int edges = 0, conforming = 0;
  const double lo = 1.0 / std::sqrt(2.0), hi = std::sqrt(2.0);
  for (const auto& [key, uses] : directed) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    auto it = directed.find(code(b, a));
    const int back = it == directed.end() ? 0 : it->second;
    if (uses == 2 && back == 0) ++q.orientation_conflicts;  // a manifold edge used twice one way
    if (back > 0 && a > b) continue;  // count each undirected edge once
    const int total = uses + back;
    if (total == 1) ++q.boundary_edges;
    if (total > 2) ++q.nonmanifold_edges;
    ++edges;
    const double len = (m.xyz[b] - m.xyz[a]).norm();
    const double r = len / h.at_xyz(0.5 * (m.xyz[a] + m.xyz[b]));
    if (r >= lo && r <= hi) ++conforming;
  }
  q.size_conformity = edges > 0 ? double(conforming) / edges : 0;
  return q;
}

}  // namespace sizemesh
