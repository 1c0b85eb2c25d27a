#include "mesher/composite_remesh.h"

#include <algorithm>
#include <map>
#include <unordered_map>

#include "core/mesh_topology.h"
#include "core/predicates.h"
#include "mesher/composite_mesh.h"
#include "mesher/junction_size.h"
#include "mesher/quality.h"
#include "mesher/self_intersection.h"

namespace sizemesh {

namespace {

// An edge shorter than this many sizes is collapsed where one end is free.
constexpr double kShortEdge = 0.6;
constexpr double kLongEdge = 1.5;
constexpr int kPasses = 3;
// Triangles under this smallest angle are worked on wherever they are.
constexpr double kFairDeg = 30.0;
constexpr int kAttempts = 3;

}  // namespace

std::unordered_set<uint64_t> kept_edges(const SurfaceMesh& s, const Geometry& g, const Topology& topo) {
  std::map<std::pair<int, int>, std::vector<int>> between;  // face pair -> curves
  {
    std::unordered_map<int, std::vector<int>> faces_of;
    for (int f = 1; f <= g.num_faces(); ++f)
      for (const FaceLoop& loop : g.face_loops(f))
        for (const CurveUse& u : loop) faces_of[u.curve].push_back(f);
    for (auto& [c, fs] : faces_of)
      for (size_t i = 0; i < fs.size(); ++i)
        for (size_t j = i + 1; j < fs.size(); ++j)
          if (fs[i] != fs[j]) between[{std::min(fs[i], fs[j]), std::max(fs[i], fs[j])}].push_back(c);
  }
  // Each edge once: from its first triangle where two share it; an edge of
  // one triangle or of more than two is kept.
  const std::vector<std::array<int, 3>> nbr = triangle_neighbours(s.tris);
  std::unordered_set<uint64_t> hard;
  for (size_t t = 0; t < s.tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint64_t key = edge_key(s.tris[t][k], s.tris[t][(k + 1) % 3]);
      const int other = nbr[t][k];
      if (other < 0) {
        hard.insert(key);
        continue;
      }
      if (other < static_cast<int>(t)) continue;
      const int f1 = s.tri_face[t], f2 = s.tri_face[other];
      if (f1 == f2) continue;
      if (topo.composite_of(f1) != topo.composite_of(f2)) {
        hard.insert(key);
        continue;
      }
      const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
      const auto it = between.find({std::min(f1, f2), std::max(f1, f2)});
      int curve = 0;
      if (it != between.end()) {
        const auto& cs = it->second;
        for (int n : {a, b})
          if (!curve && s.node_dim[n] == 1 && std::count(cs.begin(), cs.end(), s.node_entity[n])) curve = s.node_entity[n];
        if (!curve && cs.size() == 1) curve = cs[0];
        for (int c : cs)
          if (!curve && s.node_dim[a] == 0 && s.node_dim[b] == 0) {
            const int p = g.curve_start_point(c), q = g.curve_end_point(c);
            if ((p == s.node_entity[a] && q == s.node_entity[b]) || (p == s.node_entity[b] && q == s.node_entity[a]))
              curve = c;
          }
      }
      if (!curve || topo.hard(curve)) hard.insert(key);
    }
  return hard;
}

namespace {

struct Attempt {
  composite_detail::OpCount ops;
  std::vector<int> id;      // input node -> output node (-1 gone); empty when nothing changed
  std::vector<char> fresh;  // per output triangle: made or moved by the re-mesh
  int virtual_left = 0;
};

// One re-mesh of s around the seeds (nodes of virtual curves, corners of
// thin triangles) and two rings of neighbours; frozen nodes neither move nor
// seed.
Attempt remesh_once(SurfaceMesh& s, const Geometry& g, const SizeField& h, const std::unordered_set<uint64_t>& hard,
                    std::vector<char> corner, const std::vector<char>& is_virtual, const std::vector<char>& frozen) {
  Attempt at;
  const int n_in = static_cast<int>(s.xyz.size());
  for (int n = 0; n < n_in; ++n) corner[n] |= frozen[n];
  std::vector<std::vector<int>> around(n_in);
  for (const auto& t : s.tris)
    for (int k = 0; k < 3; ++k) around[t[k]].push_back(t[(k + 1) % 3]), around[t[k]].push_back(t[(k + 2) % 3]);
  std::vector<char> in(frozen);
  std::vector<int> active;
  for (int n = 0; n < n_in; ++n)
    if (is_virtual[n] && !in[n]) in[n] = 1, active.push_back(n);
  for (const auto& t : s.tris)
    if (min_angle_deg(s.xyz[t[0]], s.xyz[t[1]], s.xyz[t[2]]) < kFairDeg)
      for (int n : t)
        if (!in[n]) in[n] = 1, active.push_back(n);
  if (active.empty()) return at;
  for (int ring = 0; ring < 2; ++ring) {
    const size_t end = active.size();
    for (size_t i = 0; i < end; ++i)
      for (int m : around[active[i]])
        if (!in[m]) in[m] = 1, active.push_back(m);
  }
  composite_detail::CompositeMesh m(s, g, h, hard, corner);
  std::sort(active.begin(), active.end(), [&](int a, int b) { return m.rank(a) < m.rank(b); });
  composite_detail::OpCount& c = at.ops;
  for (int pass = 0; pass < kPasses; ++pass) {
    for (size_t i = 0; i < active.size(); ++i) {  // short edges: a free or chain node merged away
      const int n = active[i];
      if (m.star(n).empty() || m.corner(n)) continue;
      if (!(m.edge_range(n)[0] < 1.5 * kShortEdge * m.size(n))) continue;  // no edge near short
      auto nb = m.neighbours(n);
      std::sort(nb.begin(), nb.end(), [&](int x, int y) {
        return (m.xyz(x) - m.xyz(n)).squaredNorm() < (m.xyz(y) - m.xyz(n)).squaredNorm();
      });
      for (int a : nb)
        if ((m.xyz(a) - m.xyz(n)).norm() < kShortEdge * 0.5 * (m.size(a) + m.size(n)) && m.collapse(n, a, c)) break;
    }
    // Long edges split, at most one per node the pass began with; the new
    // nodes are worked on from the next step.
    for (size_t i = 0, end = active.size(); i < end; ++i) {
      const int n = active[i];
      if (m.star(n).empty() || !(m.edge_range(n)[1] > 0.67 * kLongEdge * m.size(n))) continue;  // no edge near long
      for (int a : m.neighbours(n)) {
        const double size = 0.5 * (m.size(a) + m.size(n));
        if (size > 0 && (m.xyz(a) - m.xyz(n)).norm() > kLongEdge * size && m.split(n, a, c)) {
          active.push_back(m.num_nodes() - 1);
          break;
        }
      }
    }
    for (size_t i = 0; i < active.size(); ++i)
      if (m.star_min_angle(m.star(active[i])) < composite_detail::kSmoothBelow)
        for (int a : m.neighbours(active[i])) m.flip(active[i], a, c);
    for (int n : active) m.slide(n, c);
    for (int n : active) m.smooth(n, c);
  }
  for (int n = 0; n < n_in; ++n)
    at.virtual_left += is_virtual[n] && !m.star(n).empty() && m.xyz(n) == s.xyz[n];
  if (c.collapsed + c.split + c.flipped + c.smoothed + c.slid > 0) at.id = m.write_back(&at.fresh);
  return at;
}

}  // namespace

CompositeRemeshResult remesh_composites(SurfaceMesh& s, const Geometry& g, const SizeField& h, const Topology& topo,
                                        std::vector<std::array<int, 2>>* junction) {
  CompositeRemeshResult r;
  if (!topo.enabled || s.tris.empty()) return r;
  const int n_in = static_cast<int>(s.xyz.size());
  // Nodes of virtual curves and of points no feature curve reaches.
  const std::unordered_set<uint64_t> hard = kept_edges(s, g, topo);
  std::vector<int> hard_degree(n_in, 0);
  for (uint64_t e : hard) ++hard_degree[e >> 32], ++hard_degree[e & 0xffffffffu];
  std::vector<char> corner(n_in, 0), is_virtual(n_in, 0);
  for (int n = 0; n < n_in; ++n) {
    const int e = s.node_entity[n];
    if (s.node_dim[n] == 0)
      corner[n] = (e >= 1 && e <= static_cast<int>(topo.point_corner.size()) && topo.point_corner[e - 1]) ||
                  hard_degree[n] == 1 || hard_degree[n] > 2;
    else corner[n] = hard_degree[n] == 1 || hard_degree[n] > 2;
    is_virtual[n] = hard_degree[n] == 0 && s.node_dim[n] <= 1 && !(s.node_dim[n] == 1 && topo.hard(e)) &&
                    !(s.node_dim[n] == 1 && e >= 1 && e <= static_cast<int>(topo.curve_kind.size()) &&
                      topo.curve_kind[e - 1] == CurveKind::Seam);
    r.virtual_nodes += is_virtual[n];
  }
  if (junction)  // the union placed them on both surfaces: they stay
    for (const auto& e : *junction)
      for (int n : e) corner[n] = 1;

  // Sizes near the union's junction are the ones it was meshed with: the
  // junction's segments grown away at the gradient bound (the map never saw it).
  cut_faces_detail::JunctionGradedSize graded(g, h, h.accuracy().size_slope);
  if (junction && !junction->empty()) {
    std::vector<double> along(n_in, 0.0);
    std::vector<int> count(n_in, 0);
    for (const auto& [a, b] : *junction) {
      const double len = (s.xyz[a] - s.xyz[b]).norm();
      along[a] += len, along[b] += len, ++count[a], ++count[b];
    }
    for (size_t t = 0; t < s.tris.size(); ++t)
      for (int n : s.tris[t])
        if (count[n]) graded.add(s.tri_face[t], s.xyz[n], along[n] / count[n]);
  }
  graded.finish();

  // Local operations cannot see a surface folding back within an element
  // (a thin fuselage spine, the two skins at a trailing edge): where the
  // result crosses itself, the nodes around are frozen and the re-mesh run
  // again from the input, at most kAttempts times; then the input stays.
  const SurfaceMesh input = s;
  std::vector<double> spacing(n_in, 0.0);  // each input node's longest edge
  for (const auto& t : s.tris)
    for (int k = 0; k < 3; ++k) {
      const double len = (s.xyz[t[k]] - s.xyz[t[(k + 1) % 3]]).norm();
      spacing[t[k]] = std::max(spacing[t[k]], len), spacing[t[(k + 1) % 3]] = std::max(spacing[t[(k + 1) % 3]], len);
    }
  std::vector<char> frozen(n_in, 0);
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    if (attempt > 0) s = input;
    const Attempt at = remesh_once(s, g, graded, hard, corner, is_virtual, frozen);
    if (at.id.empty()) return r;
    const SelfIntersections si = find_self_intersections(s, size_t(1) << 16, &at.fresh);
    std::vector<Vec3> crossing;  // where fresh triangles cross the surface or turn over
    auto centroid = [&](int t) { return (s.xyz[s.tris[t][0]] + s.xyz[s.tris[t][1]] + s.xyz[s.tris[t][2]]) / 3.0; };
    for (const auto& [a, b] : si.kept)
      for (int t : {a, b})
        if (at.fresh[t]) crossing.push_back(centroid(t));
    for (size_t t = 0; t < s.tris.size(); ++t)
      if (at.fresh[t] && inverted_triangle(s, g, t)) crossing.push_back(centroid(static_cast<int>(t)));
    const bool clean = crossing.empty() && si.pairs <= static_cast<long long>(si.kept.size());
    if (clean) {
      r.collapsed = at.ops.collapsed, r.split = at.ops.split, r.flipped = at.ops.flipped, r.smoothed = at.ops.smoothed;
      r.slid = at.ops.slid;
      r.virtual_nodes_left = at.virtual_left;
      if (junction)
        for (auto& e : *junction)
          for (int& n : e) n = at.id[n];
      return r;
    }
    ++r.attempts_crossing;
    for (int n = 0; n < n_in; ++n)
      for (const Vec3& x : crossing)
        if ((input.xyz[n] - x).norm() <= 4 * spacing[n]) {
          frozen[n] = 1;
          break;
        }
  }
  s = input;
  r.virtual_nodes_left = r.virtual_nodes;
  return r;
}

}  // namespace sizemesh
