// The united mesh's nodes put on their CAD faces, and the united mesh written back as a SurfaceMesh.
#include "mesher/union_to_surface.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <unordered_map>
#include <utility>

#include "core/triangle_bvh.h"
#include "mesher/self_intersection.h"
#include "mesher/snap.h"

namespace sizemesh {
namespace mesh_union_detail {
namespace {

// uv of node n on face f, from the first triangle of f that uses it.
struct NodeUV {
  std::unordered_map<uint64_t, Vec2> at;
  static uint64_t key(int n, int f) { return (uint64_t(uint32_t(n)) << 32) | uint32_t(f); }
  explicit NodeUV(const SurfaceMesh& s) {
    for (size_t t = 0; t < s.tris.size(); ++t)
      for (int k = 0; k < 3; ++k) at.emplace(key(s.tris[t][k], s.tri_face[t]), s.tri_uv[t][k]);
  }
  const Vec2* find(int n, int f) const {
    const auto it = at.find(key(n, f));
    return it == at.end() ? nullptr : &it->second;
  }
};

// The source triangle of face f nearest a point, over all of the face's
// triangles (a tree per face, built when first asked): the start of a
// projection for a node the cut or the band remesh made far from any source
// triangle it knows.
class FaceTriangles {
 public:
  explicit FaceTriangles(const SurfaceMesh& s) : s_(s) {
    for (size_t t = 0; t < s.tris.size(); ++t) of_face_[s.tri_face[t]].push_back(static_cast<int>(t));
  }
  // The nearest triangle of f to x (-1 when f has none).
  int nearest(int f, const Vec3& x) {
    auto it = tree_.find(f);
    if (it == tree_.end()) {
      const auto list = of_face_.find(f);
      if (list == of_face_.end()) return -1;
      std::vector<std::array<int, 3>> tris;
      for (int t : list->second) tris.push_back(s_.tris[t]);
      it = tree_.emplace(f, std::make_unique<TriangleBVH>(s_.xyz, tris)).first;
    }
    const TriangleBVH::Closest c = it->second->closest(x);
    return c.tri < 0 ? -1 : of_face_[f][c.tri];
  }

 private:
  const SurfaceMesh& s_;
  std::unordered_map<int, std::vector<int>> of_face_;
  std::unordered_map<int, std::unique_ptr<TriangleBVH>> tree_;
};

// Nodes put on their CAD surfaces where the surfaces graze may cross the
// other side's facets, which stay chords: the nodes of every intersecting
// pair that involves a moved node go back to their place on the meshes
// (which did not intersect there), a few rounds, then every moved node does.
// Returns the intersecting pairs left, or -1 when that last step left them
// uncounted.
long long keep_apart(SurfaceMesh& r, const std::vector<Vec3>& before_snap) {
  auto moved = [&](int t) {
    for (int n : r.tris[t])
      if (r.xyz[n] != before_snap[n]) return true;
    return false;
  };
  for (int round = 0; round < 4; ++round) {
    const SelfIntersections hits = find_self_intersections(r, static_cast<size_t>(-1));
    bool any = false;
    for (const auto& pair : hits.kept) {
      if (!moved(pair[0]) && !moved(pair[1])) continue;
      any = true;
      if (round == 3) break;
      for (int t : pair)
        for (int n : r.tris[t]) r.xyz[n] = before_snap[n];
    }
    if (!any) return hits.pairs;
    if (round == 3) r.xyz = before_snap;
  }
  return -1;
}

}  // namespace

void to_surface_mesh(SurfaceMesh& s, const Geometry& g, Tracked& base, const std::set<int>& gap_moved,
                     std::map<int, std::set<int>>& near_cut, const std::vector<int>& aside, MeshUnionResult& out) {
  Mesh& m = base.m;

  // Every node the cut or the remesh made or moved goes onto its CAD faces.
  const double diag = [&] {
    Eigen::AlignedBox3d box;
    for (const Vec3& x : s.xyz) box.extend(x);
    return box.isEmpty() ? 1.0 : box.diagonal().norm();
  }();
  const NodeUV node_uv(s);
  FaceTriangles face_tris(s);
  std::map<std::pair<uint32_t, int>, Vec2> vertex_uv;  // (vertex, face) -> uv
  std::vector<Vec3> xyz(m.number_of_vertices());
  std::map<VI, std::vector<std::pair<int, Vec2>>> junction_faces;  // cut node -> (face, uv) on each of its surfaces
  std::vector<bool> on_cut(m.number_of_vertices(), false);
  for (EI e : m.edges())
    if (base.cut[e]) on_cut[m.vertex(e, 0)] = on_cut[m.vertex(e, 1)] = true;
  for (VI v : m.vertices()) xyz[v] = vec(m.point(v));
  auto displaced = [&](FI f) {
    if (gap_moved.empty() || base.tri[f] < 0) return false;
    for (int n : s.tris[base.tri[f]])
      if (gap_moved.count(n)) return true;
    return false;
  };
  // uv on source triangle t of the point of t nearest x; `dist` its distance.
  auto uv_on = [&](int t, const Vec3& x, double& dist) {
    const auto& tr = s.tris[t];
    const Vec3 w = TriangleBVH::closest_barycentric(x, s.xyz[tr[0]], s.xyz[tr[1]], s.xyz[tr[2]]);
    dist = (w[0] * s.xyz[tr[0]] + w[1] * s.xyz[tr[1]] + w[2] * s.xyz[tr[2]] - x).norm();
    return Vec2(w[0] * s.tri_uv[t][0] + w[1] * s.tri_uv[t][1] + w[2] * s.tri_uv[t][2]);
  };
  for (VI v : m.vertices()) {
    const int n = base.node[v];
    if (n >= 0 && (xyz[v] - s.xyz[n]).norm() == 0) continue;
    // Its faces: those of the triangles around it, but for a triangle moved
    // off its surface to close a slot.
    std::vector<int> faces;
    std::vector<FI> around;
    for (FI f : CGAL::faces_around_target(m.halfedge(v), m)) {
      if (f == Mesh::null_face()) continue;
      around.push_back(f);
      if (displaced(f)) continue;
      if (std::find(faces.begin(), faces.end(), base.face[f]) == faces.end()) faces.push_back(base.face[f]);
    }
    if (faces.empty() || faces.size() > 4) continue;
    // Starts: the source triangles of the triangles around the node, else
    // the nearest source triangle of that face near a cut, else the node's uv.
    std::vector<Vec2> uv(faces.size());
    bool started = true;
    for (size_t i = 0; i < faces.size() && started; ++i) {
      double best = HUGE_VAL, d;
      for (FI f : around)
        if (base.face[f] == faces[i] && base.tri[f] >= 0) {
          const Vec2 at = uv_on(base.tri[f], xyz[v], d);
          if (d < best) best = d, uv[i] = at;
        }
      if (best > 0)
        for (int t : near_cut[faces[i]]) {
          const Vec2 at = uv_on(t, xyz[v], d);
          if (d < best) best = d, uv[i] = at;
        }
      if (best == HUGE_VAL) {
        const Vec2* known = n >= 0 ? node_uv.find(n, faces[i]) : nullptr;
        const int t = known ? -1 : face_tris.nearest(faces[i], xyz[v]);
        if (known) uv[i] = *known;
        else if (t >= 0) uv[i] = uv_on(t, xyz[v], d);
        else started = false;
      }
    }
    if (!started) continue;
    // A start read off a source triangle's corners is linear in uv, off the
    // surface by about the triangle's chord height; where the surface's
    // parametrisation is not (a strip collapsed onto a trailing edge inside
    // the triangle), it maps a good part of the triangle away: the nearest
    // point of the whole face instead.
    double source = 0;  // the longest edge of the triangles around, or of their sources
    for (FI f : around) {
      if (base.tri[f] >= 0)
        for (int k = 0; k < 3; ++k) {
          const auto& tr = s.tris[base.tri[f]];
          source = std::max(source, (s.xyz[tr[k]] - s.xyz[tr[(k + 1) % 3]]).norm());
        }
      for (Mesh::Halfedge_index e : CGAL::halfedges_around_face(m.halfedge(f), m))
        source = std::max(source, (xyz[m.source(e)] - xyz[m.target(e)]).norm());
    }
    for (size_t i = 0; i < faces.size(); ++i) {
      auto off = [&](const Vec2& at) { return (g.eval_face(faces[i], at).p - xyz[v]).norm(); };
      const double start = off(uv[i]);
      if (start <= 0.1 * source) continue;
      Vec2 at = uv[i];
      if (!g.project_to_face(faces[i], xyz[v], at)) {  // Newton stalled: the whole face
        at = uv[i];
        if (!g.nearest_on_face(faces[i], xyz[v], at)) continue;
      }
      if (off(at) < start) uv[i] = at;
    }
    for (size_t i = 0; i < faces.size(); ++i) vertex_uv[{uint32_t(v), faces[i]}] = uv[i];
    // The move stays under half the shortest edge at the node and turns no
    // triangle over; where it would (surfaces meeting at a grazing angle),
    // the node keeps its place on the meshes.
    double shortest = HUGE_VAL;
    for (VI w : CGAL::vertices_around_target(m.halfedge(v), m)) shortest = std::min(shortest, (xyz[w] - xyz[v]).norm());
    Vec3 x = xyz[v];
    std::vector<Vec2> snapped = uv;
    const bool moved = snap(g, faces, snapped, x, 0.5 * shortest, 1e-13 * diag);
    bool flips = false;
    for (FI f : around) {
      std::array<Vec3, 3> before, after;
      int k = 0;
      for (VI w : CGAL::vertices_around_face(m.halfedge(f), m)) {
        before[k] = xyz[w];
        after[k++] = w == v ? x : xyz[w];
      }
      const Vec3 nb = (before[1] - before[0]).cross(before[2] - before[0]);
      const Vec3 na = (after[1] - after[0]).cross(after[2] - after[0]);
      flips = flips || !(na.dot(nb) > 0);
    }
    if (moved && !flips) {
      xyz[v] = x;
      for (size_t i = 0; i < faces.size(); ++i) vertex_uv[{uint32_t(v), faces[i]}] = snapped[i];
    }
    if (on_cut[v])
      for (size_t i = 0; i < faces.size(); ++i) junction_faces[v].push_back({faces[i], vertex_uv[{uint32_t(v), faces[i]}]});
  }

  // The new mesh: the source nodes keep their ids (moved ones their
  // classification); new nodes follow; unused nodes are dropped.
  SurfaceMesh r;
  r.failures = s.failures;
  r.stats = s.stats;
  std::vector<int> id(m.number_of_vertices(), -1);
  std::vector<Vec3> node_xyz = s.xyz, unsnapped = s.xyz;
  std::vector<int8_t> dim = s.node_dim;
  std::vector<int> entity = s.node_entity;
  for (VI v : m.vertices()) {
    const int n = base.node[v];
    if (n >= 0) {
      id[v] = n;
      node_xyz[n] = xyz[v];
      unsnapped[n] = vec(m.point(v));
      continue;
    }
    id[v] = static_cast<int>(node_xyz.size());
    node_xyz.push_back(xyz[v]);
    unsnapped.push_back(vec(m.point(v)));
    dim.push_back(2);
    int face = 0;
    for (FI f : CGAL::faces_around_target(m.halfedge(v), m))
      if (f != Mesh::null_face()) face = face ? std::min(face, base.face[f]) : base.face[f];
    entity.push_back(face);
    out.junction_nodes += on_cut[v];
  }
  std::vector<std::array<int, 3>> tris;
  std::vector<int> tri_face;
  std::vector<std::array<Vec2, 3>> tri_uv;
  for (FI f : m.faces()) {
    const int face = base.face[f], src = base.tri[f];
    std::array<int, 3> tr;
    std::array<Vec2, 3> uv;
    int k = 0;
    for (VI v : CGAL::vertices_around_face(m.halfedge(f), m)) {
      tr[k] = id[v];
      const int n = base.node[v];
      const auto known = vertex_uv.find({uint32_t(v), face});
      if (known != vertex_uv.end()) {
        uv[k] = known->second;
      } else if (src >= 0 && n >= 0 && std::find(s.tris[src].begin(), s.tris[src].end(), n) != s.tris[src].end()) {
        uv[k] = s.tri_uv[src][std::find(s.tris[src].begin(), s.tris[src].end(), n) - s.tris[src].begin()];
      } else if (const Vec2* at = n >= 0 ? node_uv.find(n, face) : nullptr) {
        uv[k] = *at;
      } else {
        // A start on the face's nearest source triangle, then the surface.
        double d;
        const int t = face_tris.nearest(face, node_xyz[tr[k]]);
        uv[k] = t >= 0 ? uv_on(t, node_xyz[tr[k]], d) : Vec2(0, 0);
        g.project_to_face(face, node_xyz[tr[k]], uv[k]);
      }
      ++k;
    }
    // On a periodic face, the corners in one period (the first corner's).
    for (int axis = 0; axis < 2; ++axis) {
      const double period = axis == 0 ? g.face_wrap_u(face) : g.face_wrap_v(face);
      if (period > 0)
        for (int j = 1; j < 3; ++j) uv[j][axis] += period * std::round((uv[0][axis] - uv[j][axis]) / period);
    }
    tris.push_back(tr);
    tri_face.push_back(face);
    tri_uv.push_back(uv);
  }
  for (int t : aside) tris.push_back(s.tris[t]), tri_face.push_back(s.tri_face[t]), tri_uv.push_back(s.tri_uv[t]);

  // Triangles by face, in their order; nodes renumbered in theirs.
  std::vector<int> order(tris.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return tri_face[a] < tri_face[b]; });
  std::vector<int> used(node_xyz.size(), -1);
  std::vector<Vec3> before_snap;
  for (const auto& tr : tris)
    for (int n : tr) used[n] = 0;
  for (size_t n = 0; n < used.size(); ++n)
    if (used[n] == 0) {
      used[n] = static_cast<int>(r.xyz.size());
      r.xyz.push_back(node_xyz[n]);
      before_snap.push_back(unsnapped[n]);
      r.node_dim.push_back(dim[n]);
      r.node_entity.push_back(entity[n]);
    }
  for (int t : order) {
    r.tris.push_back({used[tris[t][0]], used[tris[t][1]], used[tris[t][2]]});
    r.tri_face.push_back(tri_face[t]);
    r.tri_uv.push_back(tri_uv[t]);
  }
  out.crossing_pairs = keep_apart(r, before_snap);
  for (EI e : m.edges())
    if (base.cut[e]) out.junction.push_back({used[id[m.vertex(e, 0)]], used[id[m.vertex(e, 1)]]});
  // Each junction node's distance from each of its surfaces, as it ends.
  for (auto& [v, on] : junction_faces) count_junction_node(out, g, r.xyz[used[id[v]]], std::move(on), 1e-9 * diag);
  s = std::move(r);
}

}  // namespace mesh_union_detail

void count_junction_node(MeshUnionResult& u, const Geometry& g, const Vec3& x, std::vector<std::pair<int, Vec2>> on,
                         double off) {
  double gap = 0;
  bool projected = true;
  for (auto& [face, uv] : on)
    if (g.project_to_face(face, x, uv)) gap = std::max(gap, (g.eval_face(face, uv).p - x).norm());
    else projected = false;
  if (projected) u.max_junction_gap = std::max(u.max_junction_gap, gap);
  u.junction_nodes_unprojected += !projected;
  u.junction_nodes_off += !projected || gap > off;
}

}  // namespace sizemesh
