// Triangles the corefinement left without a source adopted, and the tracked mesh renumbered by its geometry.
#include "mesher/corefine_tracking.h"

#include <algorithm>
#include <array>
#include <tuple>
#include <utility>
#include <vector>

namespace sizemesh::mesh_union_detail {

void adopt_orphans(Tracked& t) {
  const Mesh& m = t.m;
  auto normal = [&](FI f) {
    std::array<Point, 3> p;
    int k = 0;
    for (VI v : CGAL::vertices_around_face(m.halfedge(f), m)) p[k++] = m.point(v);
    return CGAL::unit_normal(p[0], p[1], p[2]);
  };
  std::vector<FI> orphans;
  for (FI f : m.faces())
    if (t.face[f] == 0) orphans.push_back(f);
  for (int pass = 0; pass < 2 && !orphans.empty(); ++pass) {
    for (bool changed = true; changed && !orphans.empty();) {
      changed = false;
      std::vector<FI> left;
      for (FI f : orphans) {
        const K::Vector_3 n = normal(f);
        FI best = Mesh::null_face();
        double best_dot = pass == 0 ? 1 - 1e-9 : -2;
        for (auto h : CGAL::halfedges_around_face(m.halfedge(f), m)) {
          const FI g = m.face(m.opposite(h));
          if (g == Mesh::null_face() || t.face[g] == 0) continue;
          const double d = CGAL::to_double(n * normal(g));
          if (d > best_dot) best_dot = d, best = g;
        }
        if (best == Mesh::null_face()) {
          left.push_back(f);
          continue;
        }
        t.face[f] = t.face[best];
        t.tri[f] = t.tri[best];
        changed = true;
      }
      orphans.swap(left);
    }
  }
}

void renumber(Tracked& t) {
  const Mesh& m = t.m;
  std::vector<VI> vertices;
  for (FI f : m.faces())
    for (VI v : CGAL::vertices_around_face(m.halfedge(f), m)) vertices.push_back(v);
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  auto key = [&](VI v) {
    const Point& p = m.point(v);
    return std::make_tuple(p.x(), p.y(), p.z(), t.node[v]);
  };
  std::stable_sort(vertices.begin(), vertices.end(), [&](VI a, VI b) { return key(a) < key(b); });
  Tracked out;
  std::vector<VI> to(m.number_of_vertices() + m.number_of_removed_vertices(), Mesh::null_vertex());
  for (VI v : vertices) {
    const VI w = out.m.add_vertex(m.point(v));
    out.node[w] = t.node[v];
    to[v.idx()] = w;
  }
  // Each triangle from its lowest new vertex, turning as before.
  std::vector<std::pair<std::array<uint32_t, 3>, FI>> faces;
  for (FI f : m.faces()) {
    std::array<uint32_t, 3> c;
    int k = 0;
    for (VI v : CGAL::vertices_around_face(m.halfedge(f), m)) c[k++] = static_cast<uint32_t>(to[v.idx()]);
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    faces.emplace_back(c, f);
  }
  std::sort(faces.begin(), faces.end());
  for (const auto& [c, f] : faces) {
    const FI g = out.m.add_face(VI(c[0]), VI(c[1]), VI(c[2]));
    if (g == Mesh::null_face()) return;  // not a manifold surface: left as it was
    out.tri[g] = t.tri[f];
    out.face[g] = t.face[f];
  }
  for (EI e : m.edges()) {
    if (!t.cut[e]) continue;
    const VI a = to[m.vertex(e, 0).idx()], b = to[m.vertex(e, 1).idx()];
    if (a == Mesh::null_vertex() || b == Mesh::null_vertex()) continue;  // on no face
    const auto h = out.m.halfedge(a, b);
    if (h != Mesh::null_halfedge()) out.cut[out.m.edge(h)] = true;
  }
  t.m = out.m;
  t.attach();
}

}  // namespace sizemesh::mesh_union_detail
