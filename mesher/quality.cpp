#include "mesher/quality.h"

#include "mesher/feature_corners.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <limits>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>

#include "core/mesh_topology.h"
#include "core/predicates.h"
#include "mesher/self_intersection.h"

namespace sizemesh {

namespace {

// Per-triangle measures, computed in parallel and reduced afterwards.
struct TriangleMeasure {
  double area = 0, inner_node_distance = 0;
  std::array<double, 3> corner_distance{};  // each corner from its triangle's face's surface at its uv
  bool zero_area = false, inverted = false;
  std::array<double, 3> edge_ratio{};  // length / h(midpoint) of edge (k, k+1)
};

// Each inner node's uv on its own face (node_entity), from a triangle of
// that face at it, else (a node of a composite face whose triangles all lie
// on neighbouring faces) the nearest point of that face; NaN where none is.
std::vector<Vec2> own_face_uv(const SurfaceMesh& m, const Geometry& g) {
  std::vector<Vec2> uv(m.xyz.size(), Vec2::Constant(std::numeric_limits<double>::quiet_NaN()));
  std::vector<char> inner(m.xyz.size(), 0);
  for (size_t t = 0; t < m.tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int n = m.tris[t][k];
      if (m.node_dim[n] != 2) continue;
      inner[n] = 1;
      if (m.node_entity[n] == m.tri_face[t]) uv[n] = m.tri_uv[t][k];
    }
  std::vector<int> alone;
  for (size_t n = 0; n < m.xyz.size(); ++n)
    if (inner[n] && !uv[n].allFinite() && m.node_entity[n] >= 1 && m.node_entity[n] <= g.num_faces())
      alone.push_back(static_cast<int>(n));
  tbb::parallel_for(size_t(0), alone.size(), [&](size_t i) {
    const int n = alone[i];
    Vec2 at = Vec2::Zero();
    if (g.nearest_on_face(m.node_entity[n], m.xyz[n], at)) uv[n] = at;
  });
  return uv;
}

TriangleMeasure measure(const SurfaceMesh& m, const Geometry& g, const SizeField& h, const std::vector<Vec2>& own_uv,
                        size_t t, int& hint) {
  TriangleMeasure r;
  const auto& tr = m.tris[t];
  const Vec3 &a = m.xyz[tr[0]], &b = m.xyz[tr[1]], &c = m.xyz[tr[2]];
  const Vec3 n = (b - a).cross(c - a);
  r.area = 0.5 * n.norm();
  r.zero_area = zero_area(a, b, c);
  r.inverted = inverted_triangle(m, g, t);
  const int f = m.tri_face[t];
  const auto& uv = m.tri_uv[t];
  for (int k = 0; k < 3; ++k) {
    double d = (g.eval_face(f, uv[k]).p - m.xyz[tr[k]]).norm();
    const int own = m.node_entity[tr[k]];
    if (m.node_dim[tr[k]] == 2 && own != f && own >= 1 && own <= g.num_faces()) {
      // A node of a composite face on another B-rep face than its
      // triangle's: measured on its own face.
      if (own_uv[tr[k]].allFinite()) d = (g.eval_face(own, own_uv[tr[k]]).p - m.xyz[tr[k]]).norm();
    }
    r.corner_distance[k] = d;
    if (m.node_dim[tr[k]] == 2) r.inner_node_distance = std::max(r.inner_node_distance, d);
    // Size at the edge's midpoint, looked up in the face's uv space.
    const int k1 = (k + 1) % 3;
    const double len = (m.xyz[tr[k1]] - m.xyz[tr[k]]).norm();
    r.edge_ratio[k] = len / h.at(f, 0.5 * (uv[k] + uv[k1]), hint);
  }
  return r;
}

// Angles of triangle t at its corners (degrees).
std::array<double, 3> corner_angles(const SurfaceMesh& m, size_t t) {
  return corner_angles_deg(m.xyz[m.tris[t][0]], m.xyz[m.tris[t][1]], m.xyz[m.tris[t][2]]);
}

// Triangles under 12 degrees that no mesh of this CAD can avoid: at a sharp
// corner (a B-rep point, or a point where a junction between united
// components meets a curve or another junction, where the face's corner, the
// angle sum of that face's triangles there, is under 12 degrees) either the
// triangle's smallest angle sits at the corner, or the triangle lies in the corner's wedge, every node
// on the two curves that meet there: where the wedge is narrower than its
// boundary segments, a triangle spanning it cannot have larger angles.
//
// And in a face narrower than the elements, every node on the face's
// boundary and the triangle spanning the face: either its shortest edge joins
// two curves (its ends are not on one curve) at under tan(12 deg) of the
// wanted size, or at most one of its edges is a segment of the boundary (it
// runs from one part of the boundary to another; the two branches of a curve
// folding back on itself count, a boundary ear does not) and its height over
// its longest edge is under tan(12 deg) of the smallest wanted size at its
// edges. The face is that narrow there, its boundary is split at about the
// wanted size, and no triangle spanning it can do better unless the size map
// goes below h_min.
void count_forced_slivers(const SurfaceMesh& m, const Geometry& g, const std::vector<TriangleMeasure>& per,
                          MeshQuality& q) {
  // Mesh nodes a and b are consecutive on a B-rep curve shorter than h: its
  // segments are as short as the CAD makes them, whatever the size map asks.
  std::map<std::pair<int, int>, double> shortest;  // B-rep point pair -> shortest curve between them
  auto shortest_between = [&](int p, int r) {
    if (shortest.empty())
      for (int c = 1; c <= g.num_curves(); ++c) {
        const auto key = std::minmax(g.curve_start_point(c), g.curve_end_point(c));
        const auto it = shortest.find(key);
        const double len = g.curve_length(c);
        if (it == shortest.end() || len < it->second) shortest[key] = len;
      }
    const auto it = shortest.find(std::minmax(p, r));
    return it == shortest.end() ? HUGE_VAL : it->second;
  };
  auto short_curve_segment = [&](int a, int b, double h) {
    const int da = m.node_dim[a], db = m.node_dim[b], ea = m.node_entity[a], eb = m.node_entity[b];
    if (da == 0 && db == 0) return shortest_between(ea, eb) < h;
    if (da == 1 && db == 1) return ea == eb && g.curve_length(ea) < h;
    if (da + db != 1) return false;
    const int curve = da == 1 ? ea : eb, point = da == 0 ? ea : eb;
    return (g.curve_start_point(curve) == point || g.curve_end_point(curve) == point) && g.curve_length(curve) < h;
  };
  // The surface's curves and corners as its faces draw them: a B-rep curve,
  // or a junction where a union of meshes cut two components' faces (the
  // curve a B-rep union would have made); a corner is a B-rep point or a
  // node where three faces meet (a junction meeting a curve or another
  // junction). A junction node is on two faces and classified on neither's
  // B-rep.
  std::vector<std::array<int, 3>> faces_at(m.xyz.size(), {-1, -1, -1});  // first three faces at each node
  for (size_t t = 0; t < m.tris.size(); ++t)
    for (int n : m.tris[t]) {
      auto& f = faces_at[n];
      const int face = m.tri_face[t];
      for (int& slot : f) {
        if (slot == face) break;
        if (slot < 0) {
          slot = face;
          break;
        }
      }
    }
  auto is_corner = [&](int n) { return m.node_dim[n] == 0 || faces_at[n][2] >= 0; };
  auto on_curve = [&](int n) { return m.node_dim[n] <= 1 || faces_at[n][1] >= 0; };
  // The curve a non-corner node lies on: (1, B-rep curve) or (2, its two faces).
  auto curve_of = [&](int n) -> std::pair<int, int64_t> {
    if (m.node_dim[n] == 1) return {1, m.node_entity[n]};
    const auto [lo, hi] = std::minmax(faces_at[n][0], faces_at[n][1]);
    return {2, (int64_t(lo) << 32) | uint32_t(hi)};
  };
  auto place_of = [&](int n) -> std::pair<int, int64_t> {
    if (is_corner(n)) return {0, n};
    return on_curve(n) ? curve_of(n) : std::pair<int, int64_t>{3, n};
  };
  auto key = [&](int node, size_t t) { return (uint64_t(node) << 32) | uint32_t(m.tri_face[t]); };
  std::unordered_map<uint64_t, double> corner;  // (corner node, face) -> angle sum
  for (size_t t = 0; t < m.tris.size(); ++t) {
    const auto& tr = m.tris[t];
    if (!is_corner(tr[0]) && !is_corner(tr[1]) && !is_corner(tr[2])) continue;
    const auto a = corner_angles(m, t);
    for (int k = 0; k < 3; ++k)
      if (is_corner(tr[k])) corner[key(tr[k], t)] += a[k];
  }
  auto sharp = [&](int node, size_t t) { return is_corner(node) && corner[key(node, t)] < kSliverDeg; };
  // Per face: its sharp corner nodes and the curves leaving them.
  std::unordered_map<int, std::set<std::pair<int, int64_t>>> wedge;  // face -> {place_of}
  for (size_t t = 0; t < m.tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int node = m.tris[t][k];
      if (!sharp(node, t)) continue;
      auto& w = wedge[m.tri_face[t]];
      w.insert(place_of(node));
      for (int j : {1, 2}) {
        const int other = m.tris[t][(k + j) % 3];
        if (!is_corner(other) && on_curve(other)) w.insert(curve_of(other));
      }
    }
  // Edges of every thin triangle, and how many triangles of its face use each:
  // one for a segment of the face's boundary, two for an edge inside it.
  auto edge_key = [&](size_t t, int k) {
    const int a = m.tris[t][k], b = m.tris[t][(k + 1) % 3];
    return std::make_tuple(std::min(a, b), std::max(a, b), m.tri_face[t]);
  };
  std::map<std::tuple<int, int, int>, int> uses;
  for (size_t t = 0; t < m.tris.size(); ++t)
    if (q.min_angle[t] < kSliverDeg)
      for (int k = 0; k < 3; ++k) uses[edge_key(t, k)] = 0;
  for (size_t t = 0; t < m.tris.size() && !uses.empty(); ++t)
    for (int k = 0; k < 3; ++k) {
      const auto it = uses.find(edge_key(t, k));
      if (it != uses.end()) ++it->second;
    }
  q.sliver.assign(m.tris.size(), 0);
  for (size_t t = 0; t < m.tris.size(); ++t) {
    if (!(q.min_angle[t] < kSliverDeg)) continue;
    const auto a = corner_angles(m, t);
    const int k = static_cast<int>(std::min_element(a.begin(), a.end()) - a.begin());
    bool forced = sharp(m.tris[t][k], t);
    const auto w = wedge.find(m.tri_face[t]);
    if (!forced && w != wedge.end()) {
      forced = true;
      for (int node : m.tris[t]) forced = forced && w->second.count(place_of(node));
    }
    if (!forced) {
      const auto& tr = m.tris[t];
      const auto& ratio = per[t].edge_ratio;
      const int e = static_cast<int>(std::min_element(ratio.begin(), ratio.end()) - ratio.begin());
      const int a = tr[e], b = tr[(e + 1) % 3];
      const bool on_boundary = on_curve(tr[0]) && on_curve(tr[1]) && on_curve(tr[2]);
      int boundary_segments = 0;
      double h = HUGE_VAL, longest = 0;
      for (int k = 0; k < 3; ++k) {
        boundary_segments += uses[edge_key(t, k)] < 2;
        const double len = (m.xyz[tr[(k + 1) % 3]] - m.xyz[tr[k]]).norm();
        longest = std::max(longest, len);
        if (ratio[k] > 0) h = std::min(h, len / ratio[k]);
      }
      const double width = longest > 0 ? 2 * per[t].area / longest : 0;  // height over the longest edge
      const bool along_curve =
          !is_corner(a) && !is_corner(b) && on_curve(a) && on_curve(b) && curve_of(a) == curve_of(b);
      // A junction from corner to corner in this one segment: a curve of the
      // united surface shorter than the elements (where a cut passes near a
      // B-rep point, between the curves that meet there).
      const bool short_junction = is_corner(a) && is_corner(b) && (m.node_dim[a] == 2 || m.node_dim[b] == 2) &&
                                  uses[edge_key(t, e)] < 2;
      const bool spans = (boundary_segments <= 1 && width < kSliverTan * h) || (!along_curve && ratio[e] < kSliverTan);
      if (on_boundary && spans) {
        forced = true;
        ++q.narrow_below_12;
      } else if (ratio[e] < kSliverTan && (short_curve_segment(a, b, (m.xyz[a] - m.xyz[b]).norm() / ratio[e]) ||
                                        short_junction)) {
        forced = true;
        ++q.short_curve_below_12;
      }
    }
    q.forced_below_12 += forced;
    q.sliver[t] = forced ? 1 : 2;
  }
  q.avoidable_below_12 = q.below_12 - q.forced_below_12;
}

// All intersecting pairs, and the local ones: in one face or in two faces
// that share a curve (other pairs are components crossing each other).
void count_self_intersections(const SurfaceMesh& m, const std::set<std::pair<int, int>>& neighbours,
                              MeshQuality& q) {
  const SelfIntersections si = find_self_intersections(m, size_t(1) << 20);
  q.self_intersections = si.pairs;
  std::set<std::pair<int, int>> local, apart;
  for (const auto& [s, t] : si.kept) {
    const int fa = std::min(m.tri_face[s], m.tri_face[t]), fb = std::max(m.tri_face[s], m.tri_face[t]);
    if (fa != fb && !neighbours.count({fa, fb})) {
      apart.insert({fa, fb});
      continue;
    }
    ++q.local_self_intersections;
    local.insert({fa, fb});
  }
  for (const auto& [fa, fb] : local) {
    if (q.intersecting_faces.size() >= 20) break;
    q.intersecting_faces.push_back({fa, fb});
  }
  for (const auto& [fa, fb] : apart) {
    if (q.crossing_faces.size() >= 20) break;
    q.crossing_faces.push_back({fa, fb});
  }
}

}  // namespace

bool inverted_triangle(const SurfaceMesh& m, const Geometry& g, size_t t) {
  const auto& tr = m.tris[t];
  const Vec3 n = (m.xyz[tr[1]] - m.xyz[tr[0]]).cross(m.xyz[tr[2]] - m.xyz[tr[0]]);
  const int f = m.tri_face[t];
  const auto& uv = m.tri_uv[t];
  const SurfaceD1 s = g.eval_face(f, (uv[0] + uv[1] + uv[2]) / 3.0);
  Vec3 ns = s.du.cross(s.dv);
  if (g.face_reversed(f)) ns = -ns;
  return ns.norm() > 0 && n.dot(ns) <= 0;
}

MeshQuality mesh_quality(const SurfaceMesh& m, const Geometry& g, const SizeField& h,
                         const std::unordered_set<uint64_t>* kept) {
  MeshQuality q;
  const size_t nt = m.tris.size();
  q.triangles = static_cast<int>(nt);
  q.nodes = static_cast<int>(m.xyz.size());
  q.min_angle.resize(nt);
  std::vector<TriangleMeasure> per(nt);
  const std::vector<Vec2> own_uv = own_face_uv(m, g);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 4096), [&](const tbb::blocked_range<size_t>& range) {
    int hint = -1;
    for (size_t t = range.begin(); t != range.end(); ++t) {
      if (t > range.begin() && m.tri_face[t] != m.tri_face[t - 1]) hint = -1;  // hints are per face
      const auto& tr = m.tris[t];
      q.min_angle[t] = min_angle_deg(m.xyz[tr[0]], m.xyz[tr[1]], m.xyz[tr[2]]);
      per[t] = measure(m, g, h, own_uv, t, hint);
    }
  });
  for (size_t t = 0; t < nt; ++t) {
    const double ang = q.min_angle[t];
    q.histogram[std::min(9, static_cast<int>(ang / 6.0))]++;
    if (ang < kSliverDeg) ++q.below_12;
    if (ang < 24) ++q.below_24;
    q.worst_angle = std::min(q.worst_angle, ang);
    q.area += per[t].area;
    q.zero_area += per[t].zero_area;
    q.inverted += per[t].inverted;
    if (per[t].inverted && q.inverted_faces.size() < 20 &&
        std::find(q.inverted_faces.begin(), q.inverted_faces.end(), m.tri_face[t]) == q.inverted_faces.end())
      q.inverted_faces.push_back(m.tri_face[t]);
    q.max_inner_node_distance = std::max(q.max_inner_node_distance, per[t].inner_node_distance);
  }
  // A node lies on the B-rep when one face of its triangles reproduces it:
  // a corner of a composite face's triangle on a curve of the neighbouring
  // B-rep face has no exact uv on the triangle's own face (its surface
  // extended past the trim), the triangles of that neighbour do.
  std::vector<double> node_distance(m.xyz.size(), HUGE_VAL);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      double& d = node_distance[m.tris[t][k]];
      d = std::min(d, per[t].corner_distance[k]);
    }
  for (double d : node_distance)
    if (d < HUGE_VAL) q.max_node_distance = std::max(q.max_node_distance, d);
  count_forced_slivers(m, g, per, q);
  if (kept) {
    const std::vector<char> corner = at_feature_corners(m, *kept, q.min_angle);
    q.feature_corner_below_12 = static_cast<int>(std::count(corner.begin(), corner.end(), 1));
  }
  // Edge uses, sorted by undirected edge: (min, max) << 1 | reversed, then the
  // use (triangle, side) so each group is one edge with its directions.
  std::vector<std::pair<uint64_t, uint32_t>> uses(3 * nt);
  tbb::parallel_for(size_t(0), nt, [&](size_t t) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.tris[t][k], b = m.tris[t][(k + 1) % 3];
      const uint64_t key = edge_key(a, b);
      uses[3 * t + k] = {key << 1 | (a > b ? 1u : 0u), static_cast<uint32_t>(3 * t + k)};
    }
  });
  tbb::parallel_sort(uses.begin(), uses.end());
  int edges = 0, conforming = 0;
  std::set<std::pair<int, int>> neighbours;  // faces sharing a mesh edge
  std::set<int> open_faces;
  const double lo = 1.0 / std::sqrt(2.0), hi = std::sqrt(2.0);
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    int forward = 0, backward = 0;
    while (j < uses.size() && (uses[j].first >> 1) == (uses[i].first >> 1)) {
      (uses[j].first & 1 ? backward : forward)++;
      ++j;
    }
    const int total = forward + backward;
    if (total == 1) ++q.boundary_edges;
    if (total > 2) ++q.nonmanifold_edges;
    if (total != 2 && open_faces.size() < 20) open_faces.insert(m.tri_face[uses[i].second / 3]);
    if (total == 2 && forward != 1) ++q.orientation_conflicts;  // a manifold edge used twice one way
    for (size_t u = i + 1; u < j; ++u) {  // faces meeting at this edge share a curve
      const int fa = m.tri_face[uses[i].second / 3], fb = m.tri_face[uses[u].second / 3];
      if (fa != fb) neighbours.insert({std::min(fa, fb), std::max(fa, fb)});
    }
    ++edges;
    const uint32_t use = uses[i].second;
    const double r = per[use / 3].edge_ratio[use % 3];
    if (r >= lo && r <= hi) ++conforming;
    i = j;
  }
  q.open_faces.assign(open_faces.begin(), open_faces.end());
  q.size_conformity = edges > 0 ? double(conforming) / edges : 0;
  count_self_intersections(m, neighbours, q);
  return q;
}

}  // namespace sizemesh
