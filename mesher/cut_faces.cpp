#include "mesher/cut_faces.h"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "mesher/junction_slivers.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "mesher/self_intersection.h"
#include "mesher/snap.h"

namespace sizemesh {
namespace {

constexpr int kRounds = 5;

uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (uint64_t(uint32_t(a)) << 32) | uint32_t(b);
}

// The edge from a to b, told apart from the edge from b to a.
uint64_t directed_key(int a, int b) { return (uint64_t(uint32_t(a)) << 32) | uint32_t(b); }

// A triangle's corners in face f's uv, shifted by whole periods into the
// period that holds its centroid: a node on the seam takes the side of the
// triangle it is a corner of.
std::array<Vec2, 3> canonical_uv(const Geometry& g, int f, std::array<Vec2, 3> u) {
  const Vec2 c = (u[0] + u[1] + u[2]) / 3.0;
  const Vec2 lo = g.face_uv_bounds(f).lo;
  for (int axis = 0; axis < 2; ++axis) {
    const double period = axis == 0 ? g.face_wrap_u(f) : g.face_wrap_v(f);
    if (!(period > 0)) continue;
    const double shift = -std::floor((c[axis] - lo[axis]) / period) * period;
    for (Vec2& x : u) x[axis] += shift;
  }
  return u;
}

// One junction polyline between two corners, and its new inner nodes.
struct Chain {
  std::vector<int> nodes;  // first to last; first == last when it closes on itself
  int fa = 0, fb = 0;      // the faces on either side
  bool usable = false;     // two faces, the same all along, with the nodes' uv on both
  std::vector<Vec3> x;     // new inner nodes: position, uv on fa and fb, node id
  std::vector<Vec2> uva, uvb;
  std::vector<int> id;
  std::vector<double> size;  // the size map at `nodes`: the finer of its two faces
};

// The mesh's edges, nodes and junction, read once.
struct Topology {
  std::unordered_map<uint64_t, std::vector<int>> edge_tris;
  std::vector<std::vector<int>> node_faces;
  std::unordered_map<uint64_t, Vec2> uv_at;  // (node, face) -> uv in a triangle of that face
  std::vector<std::vector<int>> junction_next;

  std::vector<char> on_seam;

  Topology(const SurfaceMesh& s, const Geometry& g, const std::vector<std::array<int, 2>>& junction) {
    node_faces.resize(s.xyz.size());
    junction_next.resize(s.xyz.size());
    for (size_t t = 0; t < s.tris.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const int a = s.tris[t][k], f = s.tri_face[t];
        edge_tris[edge_key(a, s.tris[t][(k + 1) % 3])].push_back(static_cast<int>(t));
        auto& faces = node_faces[a];
        if (std::find(faces.begin(), faces.end(), f) == faces.end()) faces.push_back(f);
        uv_at.emplace(key(a, f), s.tri_uv[t][k]);
      }
    // Nodes on a seam: their uv in one face span more than half a period.
    on_seam.assign(s.xyz.size(), 0);
    std::unordered_map<uint64_t, std::array<Vec2, 2>> span;  // (node, face) -> uv min, max
    for (size_t t = 0; t < s.tris.size(); ++t) {
      if (!(g.face_wrap_u(s.tri_face[t]) > 0) && !(g.face_wrap_v(s.tri_face[t]) > 0)) continue;
      const std::array<Vec2, 3> corners = canonical_uv(g, s.tri_face[t], s.tri_uv[t]);
      for (int k = 0; k < 3; ++k) {
        const Vec2& uv = corners[k];
        auto [it, fresh] = span.emplace(key(s.tris[t][k], s.tri_face[t]), std::array<Vec2, 2>{uv, uv});
        it->second[0] = it->second[0].cwiseMin(uv);
        it->second[1] = it->second[1].cwiseMax(uv);
      }
    }
    for (const auto& [k, box] : span) {
      const int f = static_cast<int>(k & 0xffffffffu), n = static_cast<int>(k >> 32);
      const Vec2 width = box[1] - box[0];
      if ((g.face_wrap_u(f) > 0 && width.x() > 0.5 * g.face_wrap_u(f)) ||
          (g.face_wrap_v(f) > 0 && width.y() > 0.5 * g.face_wrap_v(f)))
        on_seam[n] = 1;
    }
    std::unordered_set<uint64_t> seen;
    for (const auto& [a, b] : junction)
      if (a != b && edge_tris.count(edge_key(a, b)) && seen.insert(edge_key(a, b)).second) {
        junction_next[a].push_back(b);
        junction_next[b].push_back(a);
      }
  }
  static uint64_t key(int n, int f) { return (uint64_t(uint32_t(n)) << 32) | uint32_t(f); }
  const Vec2* uv(int n, int f) const {
    const auto it = uv_at.find(key(n, f));
    return it == uv_at.end() ? nullptr : &it->second;
  }
  // Where a junction ends or branches, meets a CAD curve or a third face, or
  // crosses a seam (a face's loop passes it twice).
  bool corner(const SurfaceMesh& s, int n) const {
    return junction_next[n].size() != 2 || node_faces[n].size() >= 3 || s.node_dim[n] <= 1 || on_seam[n];
  }
};

// The junction in chains from corner to corner (or closed on themselves).
std::vector<Chain> junction_chains(const SurfaceMesh& s, const Topology& topo) {
  std::vector<Chain> out;
  std::unordered_set<uint64_t> done;
  for (size_t a = 0; a < topo.junction_next.size(); ++a)
    for (int b : topo.junction_next[a]) {
      if (done.count(edge_key(static_cast<int>(a), b))) continue;
      std::vector<int> path{static_cast<int>(a), b};
      done.insert(edge_key(static_cast<int>(a), b));
      bool closed = false;
      // Forward from b, then backward from a, to a corner.
      for (int side = 0; side < 2 && !closed; ++side) {
        if (side == 1) std::reverse(path.begin(), path.end());
        while (!topo.corner(s, path.back())) {
          const int cur = path.back(), prev = path[path.size() - 2];
          int next = -1;
          for (int c : topo.junction_next[cur])
            if (c != prev) next = c;
          if (next < 0 || done.count(edge_key(cur, next))) {
            closed = next == path.front();
            if (closed) path.push_back(next);
            break;
          }
          done.insert(edge_key(cur, next));
          path.push_back(next);
          if (next == path.front()) {
            closed = true;
            break;
          }
        }
      }
      Chain c;
      c.nodes = std::move(path);
      out.push_back(std::move(c));
    }
  return out;
}

// The size map, bounded near the junction by the sizes along it grown at
// the face's gradient bound (Eq. 12, |h_i - h_j| <= ln(beta) l_ij, with the
// straight distance for the length): two components' size maps meet at a
// junction neither saw, and a face coarse where the other is fine would
// jump from the junction's size to its own within one element.
class JunctionGradedSize final : public SizeFunction {
 public:
  JunctionGradedSize(const Geometry& g, const SizeFunction& base, const std::vector<double>& slope)
      : g_(g), base_(base), slope_(slope) {}
  void add(int face, const Vec3& x, double size) {
    if (face > 0 && face < static_cast<int>(slope_.size()) && slope_[face] > 0 && size > 0 && std::isfinite(size))
      seeds_[face].push_back({size, x});
  }
  // Seeds by size, for the early stop in bound().
  void finish() {
    for (auto& [f, list] : seeds_)
      std::sort(list.begin(), list.end(), [](const Seed& a, const Seed& b) { return a.size < b.size; });
  }
  double at(int face, const Vec2& uv, int& hint) const override {
    const double h = base_.at(face, uv, hint);
    const auto it = seeds_.find(face);
    if (it == seeds_.end() || !(h > it->second.front().size)) return h;
    return bound(it->second, slope_[face], g_.eval_face(face, uv).p, h);
  }
  double at_xyz(const Vec3& x) const override { return base_.at_xyz(x); }  // no face: the size map's

 private:
  struct Seed {
    double size;
    Vec3 x;
  };
  static double bound(const std::vector<Seed>& seeds, double slope, const Vec3& x, double h) {
    for (const Seed& s : seeds) {
      if (s.size >= h) break;
      h = std::min(h, s.size + slope * (x - s.x).norm());
    }
    return h;
  }
  const Geometry& g_;
  const SizeFunction& base_;
  const std::vector<double>& slope_;
  std::map<int, std::vector<Seed>> seeds_;
};

// The chain's faces and its nodes sampled again to the size map: as many
// segments as the integral of 1/h along it (Eq. 1a-1b), each new node put on
// both surfaces.
void resample(Chain& c, const SurfaceMesh& s, const Topology& topo, const Geometry& g, const SizeFunction& h,
              double tol) {
  const auto& first = topo.edge_tris.at(edge_key(c.nodes[0], c.nodes[1]));
  if (first.size() != 2 || s.tri_face[first[0]] == s.tri_face[first[1]]) return;
  c.fa = s.tri_face[first[0]];
  c.fb = s.tri_face[first[1]];
  for (size_t i = 0; i + 1 < c.nodes.size(); ++i) {
    const auto& tris = topo.edge_tris.at(edge_key(c.nodes[i], c.nodes[i + 1]));
    if (tris.size() != 2) return;
    const int x = s.tri_face[tris[0]], y = s.tri_face[tris[1]];
    if (!((x == c.fa && y == c.fb) || (x == c.fb && y == c.fa))) return;
  }
  const size_t n = c.nodes.size();
  std::vector<Vec2> ua(n), ub(n);
  std::vector<double> w(n);
  int hint_a = -1, hint_b = -1;
  for (size_t i = 0; i < n; ++i) {
    const Vec2 *a = topo.uv(c.nodes[i], c.fa), *b = topo.uv(c.nodes[i], c.fb);
    if (!a || !b) return;
    ua[i] = i ? unwrap_uv(g, c.fa, *a, ua[i - 1]) : *a;
    ub[i] = i ? unwrap_uv(g, c.fb, *b, ub[i - 1]) : *b;
    // The junction is meshed to the finer side: the size map of each
    // component saw only its own faces.
    const double size = std::min(h.at(c.fa, ua[i], hint_a), h.at(c.fb, ub[i], hint_b));
    if (!(size > 0) || !std::isfinite(size)) return;
    w[i] = 1.0 / size;
  }
  c.size.resize(n);
  for (size_t i = 0; i < n; ++i) c.size[i] = 1.0 / w[i];
  std::vector<double> along(n, 0.0);
  for (size_t i = 1; i < n; ++i)
    along[i] = along[i - 1] + (s.xyz[c.nodes[i]] - s.xyz[c.nodes[i - 1]]).norm() * 0.5 * (w[i] + w[i - 1]);
  const bool closed = c.nodes.front() == c.nodes.back();
  const int segments = std::max(closed ? 3 : 1, static_cast<int>(std::lround(along.back())));
  size_t i = 0;
  for (int k = 1; k < segments; ++k) {
    const double at = along.back() * k / segments;
    while (i + 2 < n && along[i + 1] < at) ++i;
    const double span = along[i + 1] - along[i];
    const double t = span > 0 ? std::clamp((at - along[i]) / span, 0.0, 1.0) : 0.0;
    Vec3 x = (1 - t) * s.xyz[c.nodes[i]] + t * s.xyz[c.nodes[i + 1]];
    std::vector<Vec2> uv{(1 - t) * ua[i] + t * ua[i + 1], (1 - t) * ub[i] + t * ub[i + 1]};
    const double reach = 0.5 / std::max(w[i], w[i + 1]);
    // Surfaces that meet at a grazing angle may have no point within reach
    // on both: the chain keeps its nodes.
    if (!snap(g, {c.fa, c.fb}, uv, x, reach, tol)) return;
    c.x.push_back(x);
    c.uva.push_back(uv[0]);
    c.uvb.push_back(uv[1]);
  }
  c.usable = true;
}

// True when the loops, as polygons in uv, cross or touch nowhere but at the
// shared ends of consecutive edges (a junction that leaves the face's
// parameter domain where it meets a CAD curve at a grazing angle does not).
bool simple_loops(const FaceMesh& fm) {
  struct Seg {
    Vec2 a, b;
    int na, nb;
  };
  std::vector<Seg> seg;
  for (const auto& loop : fm.loops)
    for (size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i], b = loop[(i + 1) % loop.size()];
      seg.push_back({fm.uv[a], fm.uv[b], a, b});
    }
  auto cross = [](const Vec2& o, const Vec2& p, const Vec2& q) {
    return (p - o).x() * (q - o).y() - (p - o).y() * (q - o).x();
  };
  std::sort(seg.begin(), seg.end(),
            [](const Seg& x, const Seg& y) { return std::min(x.a.x(), x.b.x()) < std::min(y.a.x(), y.b.x()); });
  for (size_t i = 0; i < seg.size(); ++i) {
    const Seg& p = seg[i];
    if ((p.a - p.b).squaredNorm() == 0) return false;
    const double right = std::max(p.a.x(), p.b.x());
    for (size_t j = i + 1; j < seg.size() && std::min(seg[j].a.x(), seg[j].b.x()) <= right; ++j) {
      const Seg& q = seg[j];
      if (std::min(p.a.y(), p.b.y()) > std::max(q.a.y(), q.b.y()) ||
          std::min(q.a.y(), q.b.y()) > std::max(p.a.y(), p.b.y()))
        continue;
      const bool shares = p.na == q.na || p.na == q.nb || p.nb == q.na || p.nb == q.nb;
      const double d1 = cross(p.a, p.b, q.a), d2 = cross(p.a, p.b, q.b);
      const double d3 = cross(q.a, q.b, p.a), d4 = cross(q.a, q.b, p.b);
      if (shares) {
        // Edges from a shared node folding back onto each other.
        if (d1 == 0 && d2 == 0) {
          const Vec2 o = p.na == q.na || p.na == q.nb ? p.a : p.b;
          const Vec2 u = (p.na == q.na || p.na == q.nb ? p.b : p.a) - o;
          const Vec2 v = (q.na == p.na || q.na == p.nb ? q.b : q.a) - o;
          if (u.dot(v) > 0) return false;
        }
        continue;
      }
      if (((d1 > 0) != (d2 > 0) || d1 == 0 || d2 == 0) && ((d3 > 0) != (d4 > 0) || d3 == 0 || d4 == 0)) return false;
    }
  }
  return true;
}

// Two region boundaries alike: the same nodes (uv, shared node, place) in the same loops.
bool same_boundary(const FaceMesh& a, const FaceMesh& b) {
  return a.face == b.face && a.global == b.global && a.pole == b.pole && a.loops == b.loops && a.uv == b.uv &&
         a.shared_xyz == b.shared_xyz && a.tris == b.tris;
}

// The face's triangles `tris` (of `all` its triangles, the others held)
// meet at a node two or more times around it: the triangles of `all` at
// such nodes are held too, so that the rest of the face has boundary loops
// the face mesher can walk. False when there is no such node.
bool held_pinches(const SurfaceMesh& s, const std::vector<int>& all, const std::vector<int>& tris, std::set<int>& held) {
  if (tris.size() == all.size()) return false;
  std::unordered_set<uint64_t> directed;
  for (int t : tris)
    for (int k = 0; k < 3; ++k) directed.insert(directed_key(s.tris[t][k], s.tris[t][(k + 1) % 3]));
  std::unordered_map<int, int> leaving;  // node -> boundary edges leaving it
  for (int t : tris)
    for (int k = 0; k < 3; ++k) {
      const int a = s.tris[t][k], b = s.tris[t][(k + 1) % 3];
      if (!directed.count(directed_key(b, a))) ++leaving[a];
    }
  bool grew = false;
  for (int t : all)
    for (int n : s.tris[t])
      if (const auto it = leaving.find(n); it != leaving.end() && it->second > 1) grew = held.insert(t).second || grew;
  return grew;
}

// A face's regions as the face mesher takes them: boundary loops (face on
// the left in uv) with the substituted chains' new nodes in place of their
// old ones. Empty when a region's boundary cannot be walked (a pole, a
// pinched corner) or holds no single outer loop.
struct Region {
  FaceMesh boundary;
  bool flip = false;  // the face's triangles run clockwise in uv
};
std::vector<Region> face_regions(const SurfaceMesh& s, const Geometry& g, int f, const std::vector<int>& tris,
                                 const std::vector<Chain>& chains, const std::vector<int>& chain_of_edge_owner,
                                 const std::unordered_map<uint64_t, int>& chain_of_edge, bool& ok) {
  ok = false;
  // Corners: a node once per wrap of a face that meets itself across a seam
  // (Geometry::face_wrap_u/v: a seam's nodes twice).
  const double period[2] = {g.face_wrap_u(f), g.face_wrap_v(f)};
  std::vector<int> node;
  std::vector<Vec2> uv;
  std::unordered_map<int, std::vector<int>> of_node;
  auto corner = [&](int n, const Vec2& at) {
    auto& list = of_node[n];
    for (int c : list) {
      bool same = true;
      for (int axis = 0; axis < 2; ++axis)
        same = same && (!(period[axis] > 0) || std::abs(uv[c][axis] - at[axis]) < 0.25 * period[axis]);
      if (same) return c;
    }
    list.push_back(static_cast<int>(node.size()));
    node.push_back(n);
    uv.push_back(at);
    return list.back();
  };
  std::vector<std::array<Vec2, 3>> tuv;
  double area = 0;
  for (int t : tris) {
    const std::array<Vec2, 3> u = canonical_uv(g, f, s.tri_uv[t]);
    tuv.push_back(u);
    area += (u[1] - u[0]).x() * (u[2] - u[0]).y() - (u[1] - u[0]).y() * (u[2] - u[0]).x();
  }
  const bool flip = area < 0;
  std::vector<std::array<int, 3>> ct;
  for (size_t i = 0; i < tris.size(); ++i) {
    const int t = tris[i];
    std::array<int, 3> c{corner(s.tris[t][0], tuv[i][0]), corner(s.tris[t][1], tuv[i][1]),
                         corner(s.tris[t][2], tuv[i][2])};
    if (flip) std::swap(c[1], c[2]);
    ct.push_back(c);
  }
  std::unordered_map<uint64_t, int> directed;
  for (const auto& c : ct)
    for (int k = 0; k < 3; ++k)
      if (++directed[directed_key(c[k], c[(k + 1) % 3])] > 1) return {};
  std::vector<int> next(node.size(), -1);
  std::vector<int> parent(node.size());
  for (size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const auto& c : ct) {
    parent[find(c[1])] = find(c[0]);
    parent[find(c[2])] = find(c[0]);
    for (int k = 0; k < 3; ++k) {
      const int a = c[k], b = c[(k + 1) % 3];
      if (directed.count(directed_key(b, a))) continue;
      if (next[a] >= 0) return {};  // two boundary edges leave one corner
      next[a] = b;
    }
  }
  // Loops, each with its region (the root of its corners).
  std::map<int, std::vector<std::vector<int>>> loops;
  std::vector<char> walked(node.size(), 0);
  for (size_t start = 0; start < node.size(); ++start) {
    if (next[start] < 0 || walked[start]) continue;
    std::vector<int> loop;
    for (int c = static_cast<int>(start); !walked[c]; c = next[c]) {
      walked[c] = 1;
      loop.push_back(c);
      if (next[c] < 0) return {};
    }
    if (loop.back() < 0 || next[loop.back()] != static_cast<int>(start) || loop.size() < 3) return {};
    loops[find(static_cast<int>(start))].push_back(std::move(loop));
  }
  std::vector<Region> out;
  for (auto& [root, list] : loops) {
    // The outer loop first: the one loop of positive area.
    std::vector<double> a(list.size(), 0.0);
    int positive = 0;
    for (size_t l = 0; l < list.size(); ++l) {
      const auto& loop = list[l];
      for (size_t i = 0; i < loop.size(); ++i) {
        const Vec2 &p = uv[loop[i]], &q = uv[loop[(i + 1) % loop.size()]];
        a[l] += p.x() * q.y() - p.y() * q.x();
      }
      positive += a[l] > 0;
    }
    if (positive != 1) return {};
    const size_t outer = std::max_element(a.begin(), a.end()) - a.begin();
    std::swap(list[0], list[outer]);
    Region r;
    r.flip = flip;
    r.boundary.face = f;
    for (const auto& loop : list) {
      // Start where no substituted chain runs through.
      size_t start = loop.size();
      for (size_t i = 0; i < loop.size() && start == loop.size(); ++i)
        if (chain_of_edge_owner[node[loop[i]]] < 0) start = i;
      if (start == loop.size()) return {};
      std::vector<int> ids;
      auto add = [&](int id, const Vec2& at, const Vec3& x) {
        SurfaceSample none;  // mesh_within() evaluates the surface
        none.p = none.du = none.dv = none.n = Vec3::Zero();
        ids.push_back(r.boundary.add_node(at, none, id));
        r.boundary.shared_xyz.back() = x;
      };
      for (size_t step = 0; step < loop.size();) {
        const int c = loop[(start + step) % loop.size()];
        const int d = loop[(start + step + 1) % loop.size()];
        add(node[c], uv[c], s.xyz[node[c]]);
        const auto it = chain_of_edge.find(edge_key(node[c], node[d]));
        if (it == chain_of_edge.end()) {
          ++step;
          continue;
        }
        const Chain& ch = chains[it->second];
        const size_t m = ch.nodes.size();
        const bool forward = ch.nodes[0] == node[c] && ch.nodes[1] == node[d];
        if (!forward && !(ch.nodes[m - 1] == node[c] && ch.nodes[m - 2] == node[d])) return {};
        // The old nodes along the chain must be the loop's next corners.
        for (size_t j = 1; j + 1 < m; ++j)
          if (node[loop[(start + step + j) % loop.size()]] != ch.nodes[forward ? j : m - 1 - j]) return {};
        Vec2 prev = uv[c];
        const size_t k = ch.x.size();
        for (size_t j = 0; j < k; ++j) {
          const size_t q = forward ? j : k - 1 - j;
          const Vec2 at = unwrap_uv(g, f, f == ch.fa ? ch.uva[q] : ch.uvb[q], prev);
          add(ch.id[q], at, ch.x[q]);
          prev = at;
        }
        step += m - 1;
      }
      if (ids.size() < 3) return {};
      r.boundary.loops.push_back(std::move(ids));
    }
    if (!simple_loops(r.boundary)) return {};
    out.push_back(std::move(r));
  }
  ok = !out.empty();
  return out;
}

// Boundary plus non-manifold edges: a rebuilt mesh must not have more.
size_t open_edges(const SurfaceMesh& s) {
  std::unordered_map<uint64_t, int> uses;
  for (const auto& t : s.tris)
    for (int k = 0; k < 3; ++k) ++uses[edge_key(t[k], t[(k + 1) % 3])];
  size_t n = 0;
  for (const auto& [e, u] : uses) n += u != 2;
  return n;
}

// Nodes at one point merged (a cut that meets a CAD curve makes one on each
// side of it), and the triangles that collapse with them dropped; the
// junction's edges follow. Nothing changes when a merge would open an edge.
// True when s changed.
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

// The parameter of curve c nearest x: the nearest of a few samples, then
// Newton on (C(t) - x) . C'(t) = 0 within the curve's range.
bool nearest_on_curve(const Geometry& g, int c, const Vec3& x, double& t) {
  double t0, t1;
  g.curve_range(c, t0, t1);
  if (!(t1 > t0)) return false;
  constexpr int kSamples = 64;
  double best = HUGE_VAL;
  for (int k = 0; k <= kSamples; ++k) {
    const double s = t0 + (t1 - t0) * k / kSamples;
    const double d = (g.eval_curve(c, s) - x).squaredNorm();
    if (d < best) best = d, t = s;
  }
  for (int it = 0; it < 20; ++it) {
    const Vec3 d = g.eval_curve(c, t) - x, tan = g.curve_tangent(c, t);
    const double tt = tan.squaredNorm();
    if (!(tt > 0)) break;
    const double step = d.dot(tan) / tt;
    t = std::clamp(t - step, t0, t1);
    if (std::abs(step) <= 1e-12 * (t1 - t0)) break;
  }
  return std::isfinite(t);
}

// The CAD curve segments that end at a junction corner (where the cut
// crossed a curve), spaced again before the faces are meshed again; only
// segments whose faces are all the corner's (faces the junction cuts) change.
//  - A node closer to the corner than a third of its other segment moves
//    along the curve to midway between its other neighbour and the corner:
//    the cut split a segment near one end, and the stub would be the short
//    side of a sliver in both faces.
//  - A segment longer than 1.5 times the size wanted at its middle is split
//    on the curve to the sizes wanted along it: the curve keeps the spacing
//    of a component's own, coarser size map, while the junction and the
//    region beside it take the finer side's, growing away from it. Not
//    where the junction leaves the corner within 15 degrees of the curve.
//  - Any other curve segment between two faces the junction cuts is split
//    so too where it is longer than 1.5 times the size wanted once the
//    junction's sizes grow into those faces (a strake's junction running
//    beside the fuselage's side curve).
// Triangles at a moved node keep their corners' uv in step; the two beside a
// split segment become fans. True when anything changed.
bool space_curve_nodes(SurfaceMesh& s, const Geometry& g, const SizeFunction& h,
                       const std::vector<double>& size_slope, const std::vector<std::array<int, 2>>& junction) {
  bool changed = false;
  std::vector<char> on_junction(s.xyz.size(), 0);
  std::unordered_map<int, std::vector<int>> junction_next;
  for (const auto& [a, b] : junction) {
    on_junction[a] = on_junction[b] = 1;
    junction_next[a].push_back(b);
    junction_next[b].push_back(a);
  }
  std::vector<std::vector<int>> node_faces(s.xyz.size()), node_tris(s.xyz.size());
  std::unordered_map<uint64_t, std::vector<int>> edge_tris;
  for (size_t t = 0; t < s.tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = s.tris[t][k], f = s.tri_face[t];
      node_tris[a].push_back(static_cast<int>(t));
      if (std::find(node_faces[a].begin(), node_faces[a].end(), f) == node_faces[a].end()) node_faces[a].push_back(f);
      edge_tris[edge_key(a, s.tris[t][(k + 1) % 3])].push_back(static_cast<int>(t));
    }
  auto corner_of = [&](int t, int n) {
    return static_cast<int>(std::find(s.tris[t].begin(), s.tris[t].end(), n) - s.tris[t].begin());
  };
  // Neighbours of a along edges between two faces (the face boundaries through a).
  auto boundary_neighbours = [&](int a) {
    std::vector<int> out;
    for (int t : node_tris[a])
      for (int b : s.tris[t]) {
        if (b == a || std::find(out.begin(), out.end(), b) != out.end()) continue;
        const auto& tris = edge_tris[edge_key(a, b)];
        if (tris.size() == 2 && s.tri_face[tris[0]] != s.tri_face[tris[1]]) out.push_back(b);
      }
    return out;
  };
  // The point of `curve` nearest x, from the curve itself: snap() onto its
  // two faces does not converge where they meet tangent (a leading edge
  // split into upper and lower skins).
  auto on_curve = [&](int curve, const Vec3& x, Vec3& p) {
    double t = 0;
    try {
      if (!nearest_on_curve(g, curve, x, t)) return false;
      p = g.eval_curve(curve, t);
    } catch (const EvaluationError&) {
      return false;
    }
    return std::isfinite(p.x());
  };
  struct Split {
    int c, a, curve;
    std::vector<Vec3> x;  // new nodes from c to a
  };
  std::vector<Split> splits;
  std::set<int> split_tris;
  // The nodes that split the segment from node `from` to node `to` of
  // `curve` into `pieces` of equal integral of 1/h (Eq. 1a-1b), `integral`
  // being its running value over equal steps from `from`: each put on the
  // curve nearest its place along the chord. False when one is not within a
  // quarter of the segment of that place.
  auto place_on_curve = [&](int from, int to, int curve, const std::vector<double>& integral, int pieces,
                            std::vector<Vec3>& out) {
    const int steps = static_cast<int>(integral.size()) - 1;
    const double length = (s.xyz[to] - s.xyz[from]).norm();
    int step = 0;
    for (int i = 1; i < pieces; ++i) {
      const double at = integral.back() * i / pieces;
      while (step + 1 < steps && integral[step + 1] < at) ++step;
      const double span = integral[step + 1] - integral[step];
      const double d = length * (step + (span > 0 ? (at - integral[step]) / span : 0.0)) / steps;
      Vec3 x;
      const Vec3 target = s.xyz[from] + (s.xyz[to] - s.xyz[from]) * (d / length);
      if (!on_curve(curve, target, x) || !((x - target).norm() < 0.25 * length)) return false;
      out.push_back(x);
    }
    return true;
  };
  for (size_t c = 0; c < s.xyz.size(); ++c) {
    if (!on_junction[c] || s.node_dim[c] != 2 || node_faces[c].size() < 3) continue;
    for (int a : boundary_neighbours(static_cast<int>(c))) {
      if (s.node_dim[a] != 1 || on_junction[a]) continue;
      bool inside = true;
      for (int f : node_faces[a])
        inside = inside && std::find(node_faces[c].begin(), node_faces[c].end(), f) != node_faces[c].end();
      const std::vector<int> along = boundary_neighbours(a);
      if (!inside || along.size() != 2) continue;
      const int p = along[0] == static_cast<int>(c) ? along[1] : along[0], curve = s.node_entity[a];
      const double stub = (s.xyz[a] - s.xyz[c]).norm(), other = (s.xyz[p] - s.xyz[a]).norm();
      const auto& beside = edge_tris[edge_key(static_cast<int>(c), a)];
      if (stub < other / 3) {
        Vec3 x;
        const Vec3 target = 0.5 * (s.xyz[p] + s.xyz[c]);
        if (!on_curve(curve, target, x) || !((x - target).norm() < 0.25 * other)) continue;
        std::map<int, Vec2> uv;  // per face of a
        bool projected = true;
        for (int t : node_tris[a]) {
          const int f = s.tri_face[t];
          if (uv.count(f)) continue;
          Vec2 w = s.tri_uv[t][corner_of(t, a)];
          projected = projected && g.project_to_face(f, x, w);
          uv[f] = w;
        }
        if (!projected) continue;
        s.xyz[a] = x;
        for (int t : node_tris[a]) {
          const int k = corner_of(t, a);
          s.tri_uv[t][k] = unwrap_uv(g, s.tri_face[t], uv[s.tri_face[t]], s.tri_uv[t][k]);
        }
        changed = true;
        continue;
      }
      // Sizes along the segment: at the corner the finest of its faces (the
      // junction is meshed to the finer component), at a the finer of its
      // two, between them linear but grown from the corner's at no more than
      // the gradient bound (Eq. 12); the segment split by the integral of 1/h
      // (Eq. 1a-1b, as a CAD curve).
      double hc = HUGE_VAL, ha = HUGE_VAL, slope = 0;  // slope 0: no bound known
      for (int t : node_tris[c]) {
        int hint = -1;
        hc = std::min(hc, h.at(s.tri_face[t], s.tri_uv[t][corner_of(t, static_cast<int>(c))], hint));
      }
      for (int t : beside) {
        int hint = -1;
        ha = std::min(ha, h.at(s.tri_face[t], s.tri_uv[t][corner_of(t, a)], hint));
        const int f = s.tri_face[t];
        if (f < static_cast<int>(size_slope.size()) && size_slope[f] > 0)
          slope = slope > 0 ? std::min(slope, size_slope[f]) : size_slope[f];
      }
      if (!(hc > 0) || !(ha > 0) || !std::isfinite(hc) || !std::isfinite(ha)) continue;
      constexpr int kSteps = 64;
      std::vector<double> integral(kSteps + 1, 0.0);
      auto size_at = [&](double d) {
        const double linear = hc + (ha - hc) * d / stub;
        return slope > 0 ? std::min(linear, hc + slope * d) : linear;
      };
      for (int i = 1; i <= kSteps; ++i) {
        const double d0 = stub * (i - 1) / kSteps, d1 = stub * i / kSteps;
        integral[i] = integral[i - 1] + (d1 - d0) * 0.5 * (1 / size_at(d0) + 1 / size_at(d1));
      }
      const int pieces = std::min(32, static_cast<int>(std::lround(integral.back())));
      if (pieces < 2 || !(stub > 1.5 * size_at(0.5 * stub))) continue;
      // Not in a narrow wedge between the curve and the junction: its
      // triangles span it from side to side, and finer nodes on one side
      // only make them thinner.
      bool wedge = false;
      const Vec3 along_curve = (s.xyz[a] - s.xyz[c]).normalized();
      for (int j : junction_next[static_cast<int>(c)])
        wedge = wedge || along_curve.dot((s.xyz[j] - s.xyz[c]).normalized()) > std::cos(15.0 * kPi / 180.0);
      if (wedge) continue;
      if (beside.size() != 2 || split_tris.count(beside[0]) || split_tris.count(beside[1])) continue;
      Split sp{static_cast<int>(c), a, curve, {}};
      if (!place_on_curve(static_cast<int>(c), a, curve, integral, pieces, sp.x)) continue;
      split_tris.insert(beside.begin(), beside.end());
      splits.push_back(std::move(sp));
    }
  }
  // Curve segments inside the faces the junction cuts, longer than 1.5
  // times the size wanted along them once the junction's sizes grow into
  // those faces (Eq. 12 from every junction node, as the faces are meshed
  // again): a segment keeps its component's coarser spacing, and the
  // region between it and a finer junction running beside it is a row of
  // caps. Split on the curve by the integral of 1/h, as above.
  std::set<int> cut;
  for (const auto& [a, b] : junction)
    for (int t : edge_tris[edge_key(a, b)]) cut.insert(s.tri_face[t]);
  JunctionGradedSize graded(g, h, size_slope);
  for (size_t n = 0; n < s.xyz.size(); ++n) {
    if (!on_junction[n]) continue;
    double size = HUGE_VAL;
    for (int t : node_tris[n]) {
      int hint = -1;
      size = std::min(size, h.at(s.tri_face[t], s.tri_uv[t][corner_of(t, static_cast<int>(n))], hint));
    }
    for (int f : node_faces[n]) graded.add(f, s.xyz[n], size);
  }
  graded.finish();
  for (const auto& [key, beside] : edge_tris) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    if (s.node_dim[a] > 1 || s.node_dim[b] > 1 || on_junction[a] || on_junction[b] || beside.size() != 2) continue;
    if (s.node_dim[a] == 0 && s.node_dim[b] == 0) continue;
    if (s.node_dim[a] == 1 && s.node_dim[b] == 1 && s.node_entity[a] != s.node_entity[b]) continue;
    if (!cut.count(s.tri_face[beside[0]]) || !cut.count(s.tri_face[beside[1]])) continue;
    if (split_tris.count(beside[0]) || split_tris.count(beside[1])) continue;
    const int curve = s.node_dim[a] == 1 ? s.node_entity[a] : s.node_entity[b];
    const double length = (s.xyz[b] - s.xyz[a]).norm();
    // Sizes along the segment, the finer of its two faces'.
    constexpr int kSteps = 16;
    std::array<double, kSteps + 1> size{};
    bool sized = true;
    for (int i = 0; i <= kSteps && sized; ++i) {
      size[i] = HUGE_VAL;
      for (int t : beside) {
        const Vec2 ua = s.tri_uv[t][corner_of(t, a)], ub = s.tri_uv[t][corner_of(t, b)];
        int hint = -1;
        size[i] = std::min(size[i], graded.at(s.tri_face[t], ua + (ub - ua) * (double(i) / kSteps), hint));
      }
      sized = size[i] > 0 && std::isfinite(size[i]);
    }
    if (!sized || !(length > 1.5 * size[kSteps / 2])) continue;
    std::vector<double> integral(kSteps + 1, 0.0);
    for (int i = 1; i <= kSteps; ++i)
      integral[i] = integral[i - 1] + length / kSteps * 0.5 * (1 / size[i - 1] + 1 / size[i]);
    const int pieces = std::min(32, static_cast<int>(std::lround(integral.back())));
    if (pieces < 2) continue;
    Split sp{a, b, curve, {}};
    if (!place_on_curve(a, b, curve, integral, pieces, sp.x)) continue;
    split_tris.insert(beside.begin(), beside.end());
    splits.push_back(std::move(sp));
  }
  // Each split: the new nodes, and the two triangles beside the segment
  // replaced by fans to their third corner.
  std::vector<char> dropped(s.tris.size(), 0);
  const size_t old_tris = s.tris.size();
  for (const Split& sp : splits) {
    const auto beside = edge_tris[edge_key(sp.c, sp.a)];
    // uv along the segment in each face beside it, by projection from the straight line.
    std::vector<std::vector<Vec2>> w(beside.size());
    bool projected = true;
    for (size_t j = 0; j < beside.size() && projected; ++j) {
      const int t = beside[j], f = s.tri_face[t];
      const Vec2 uc = s.tri_uv[t][corner_of(t, sp.c)], ua = s.tri_uv[t][corner_of(t, sp.a)];
      w[j].push_back(uc);
      for (size_t i = 0; i < sp.x.size() && projected; ++i) {
        const double at = double(i + 1) / (sp.x.size() + 1);
        const Vec2 line = (1 - at) * uc + at * ua;
        Vec2 guess = line;
        projected = g.project_to_face(f, sp.x[i], guess);
        w[j].push_back(unwrap_uv(g, f, guess, line));
      }
      w[j].push_back(ua);
    }
    if (!projected) continue;
    std::vector<int> ids{sp.c};
    for (const Vec3& x : sp.x) {
      ids.push_back(static_cast<int>(s.xyz.size()));
      s.xyz.push_back(x);
      s.node_dim.push_back(1);
      s.node_entity.push_back(sp.curve);
    }
    ids.push_back(sp.a);
    for (size_t j = 0; j < beside.size(); ++j) {
      const int t = beside[j], f = s.tri_face[t];
      const auto tr = s.tris[t];
      const auto uv = s.tri_uv[t];
      const int kc = corner_of(t, sp.c), ka = corner_of(t, sp.a), ko = 3 - kc - ka;
      const bool forward = (kc + 1) % 3 == ka;  // the triangle runs c -> a
      dropped[t] = 1;
      for (size_t i = 0; i + 1 < ids.size(); ++i) {
        if (forward) {
          s.tris.push_back({ids[i], ids[i + 1], tr[ko]});
          s.tri_uv.push_back({w[j][i], w[j][i + 1], uv[ko]});
        } else {
          s.tris.push_back({ids[i + 1], ids[i], tr[ko]});
          s.tri_uv.push_back({w[j][i + 1], w[j][i], uv[ko]});
        }
        s.tri_face.push_back(f);
      }
    }
    changed = true;
  }
  if (splits.empty()) return changed;
  size_t out = 0;
  for (size_t t = 0; t < s.tris.size(); ++t) {
    if (t < old_tris && dropped[t]) continue;
    s.tris[out] = s.tris[t];
    s.tri_face[out] = s.tri_face[t];
    s.tri_uv[out] = s.tri_uv[t];
    ++out;
  }
  s.tris.resize(out);
  s.tri_face.resize(out);
  s.tri_uv.resize(out);
  return changed;
}

// The junction's nodes, and each one's largest distance from the surfaces
// of the faces around it; `off` is the distance that counts as off them.
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

}  // namespace

CutFacesResult remesh_cut_faces(SurfaceMesh& s, const Geometry& g, const SizeFunction& h, const MeshOptions& o,
                                MeshUnionResult& u) {
  CutFacesResult out;
  std::vector<std::array<int, 2>> junction = u.junction;
  if (junction.empty()) return out;
  Eigen::AlignedBox3d box;
  for (const Vec3& x : s.xyz) box.extend(x);
  const double tol = 1e-13 * (box.isEmpty() ? 1.0 : box.diagonal().norm());
  bool merged = merge_coincident(s, junction, 1e3 * tol);
  merged = space_curve_nodes(s, g, h, o.size_slope, junction) || merged;
  const Topology topo(s, g, junction);
  std::vector<Chain> chains = junction_chains(s, topo);
  std::vector<Vec3> xyz = s.xyz;
  JunctionGradedSize graded(g, h, o.size_slope);
  for (Chain& c : chains) {
    if (c.nodes.size() < 2) continue;
    resample(c, s, topo, g, h, tol);
    for (const Vec3& x : c.x) {
      c.id.push_back(static_cast<int>(xyz.size()));
      xyz.push_back(x);
    }
    for (size_t i = 0; i < c.size.size(); ++i)
      for (int f : {c.fa, c.fb}) graded.add(f, s.xyz[c.nodes[i]], c.size[i]);
  }
  graded.finish();
  // The faces on either side of a junction, and those the union's band
  // remesh reached: its uniform length splits the CAD curves it crosses, and
  // a face beyond them is left with fans of slivers on each split edge.
  std::set<int> cut = u.band_faces;
  for (const Chain& c : chains)
    for (size_t j = 0; j + 1 < c.nodes.size(); ++j)
      for (int t : topo.edge_tris.at(edge_key(c.nodes[j], c.nodes[j + 1]))) cut.insert(s.tri_face[t]);
  std::map<int, std::vector<int>> tris_of;
  for (size_t t = 0; t < s.tris.size(); ++t)
    if (cut.count(s.tri_face[t])) tris_of[s.tri_face[t]].push_back(static_cast<int>(t));

  const size_t open_before = open_edges(s);
  // More crossing pairs than s had before its faces were meshed again. The
  // union counted the pairs of the mesh it made; a merge or a spaced curve
  // may change that, so s is counted again (once) when a round's result has
  // more than the union's count.
  long long crossing_before = !merged && u.crossing_pairs >= 0 ? u.crossing_pairs : -1;
  auto more_crossings = [&](long long pairs) {
    if (crossing_before < 0 && u.crossing_pairs >= 0 && pairs <= u.crossing_pairs) return false;
    if (crossing_before < 0) crossing_before = find_self_intersections(s, 0).pairs;
    return pairs > crossing_before;
  };
  std::set<int> kept;        // faces left with their triangles
  std::set<size_t> frozen;   // chains that keep their nodes
  std::set<int> held;        // triangles of faces meshed again that stay, with their nodes
  std::map<int, std::vector<Eigen::AlignedBox3d>> old_boxes;  // by face, of tris_of's triangles
  // Regions meshed in an earlier round, by face: the boundary given and the
  // mesh made. A round meshes again only the regions whose boundary changed
  // (those next to a face that now keeps its triangles).
  std::map<int, std::vector<std::pair<FaceMesh, FaceMesh>>> meshed_before;
  for (int round = 0; round < kRounds; ++round) {
    // Chains substituted: both faces meshed again. A face whose boundary
    // cannot be walked keeps its triangles; that changes which chains are
    // substituted, so until nothing changes.
    std::vector<int> owner(xyz.size(), -1);
    std::unordered_map<uint64_t, int> chain_of_edge;
    std::map<int, std::vector<Region>> regions;
    for (bool changed = true; changed;) {
      changed = false;
      std::fill(owner.begin(), owner.end(), -1);
      chain_of_edge.clear();
      for (size_t k = 0; k < chains.size(); ++k) {
        const Chain& c = chains[k];
        if (!c.usable || frozen.count(k) || kept.count(c.fa) || kept.count(c.fb)) continue;
        for (size_t j = 0; j + 1 < c.nodes.size(); ++j) chain_of_edge[edge_key(c.nodes[j], c.nodes[j + 1])] = k;
        for (size_t j = 1; j + 1 < c.nodes.size(); ++j) owner[c.nodes[j]] = static_cast<int>(k);
      }
      regions.clear();
      for (const auto& [f, all_tris] : tris_of) {
        if (kept.count(f)) continue;
        std::vector<int> tris;
        for (int t : all_tris)
          if (!held.count(t)) tris.push_back(t);
        bool ok = false;
        auto r = face_regions(s, g, f, tris, chains, owner, chain_of_edge, ok);
        if (!ok && held_pinches(s, all_tris, tris, held)) {
          changed = true;
          break;
        }
        if (!ok) {
          // First with its junctions' old nodes, then as it is.
          bool froze = false;
          for (size_t k = 0; k < chains.size(); ++k)
            if ((chains[k].fa == f || chains[k].fb == f) && chains[k].usable) froze = frozen.insert(k).second || froze;
          if (!froze) kept.insert(f);
          changed = true;
          break;
        }
        regions[f] = std::move(r);
      }
    }
    // Every region meshed (in parallel: faces are independent).
    std::vector<Region*> all;
    for (auto& [f, list] : regions)
      for (Region& r : list) all.push_back(&r);
    std::vector<char> meshed(all.size(), 0);
    std::vector<const FaceMesh*> earlier(all.size(), nullptr);
    for (size_t i = 0; i < all.size(); ++i)
      for (const auto& [given, made] : meshed_before[all[i]->boundary.face])
        if (same_boundary(given, all[i]->boundary)) earlier[i] = &made;
    std::vector<FaceMesh> given(all.size());
    tbb::parallel_for(size_t(0), all.size(), [&](size_t i) {
      if (earlier[i]) {
        all[i]->boundary = *earlier[i];
        meshed[i] = 1;
        return;
      }
      given[i] = all[i]->boundary;
      std::string why;
      meshed[i] = mesh_within(g, graded, all[i]->boundary, o, why);
      // A front that cannot close a region at the graded sizes (a junction
      // that hooks back on a face with a stretched parametrisation) may at
      // the size map's own.
      if (!meshed[i]) {
        all[i]->boundary = given[i];
        meshed[i] = mesh_within(g, h, all[i]->boundary, o, why);
      }
    });
    for (size_t i = 0; i < all.size(); ++i)
      if (meshed[i] && !earlier[i]) meshed_before[all[i]->boundary.face].emplace_back(std::move(given[i]), all[i]->boundary);
    bool failed = false;
    for (size_t i = 0; i < all.size(); ++i)
      if (!meshed[i]) kept.insert(all[i]->boundary.face), failed = true;
    if (failed) continue;

    // The new mesh: the faces meshed again replace their triangles.
    SurfaceMesh r;
    r.failures = s.failures;
    r.stats = s.stats;
    r.xyz = xyz;
    r.node_dim = s.node_dim;
    r.node_entity = s.node_entity;
    for (const Chain& c : chains)
      for (size_t j = 0; j < c.id.size(); ++j) {
        r.node_dim.push_back(2);
        r.node_entity.push_back(std::min(c.fa, c.fb));
      }
    std::vector<std::array<int, 3>> tris;
    std::vector<int> tri_face, fresh;
    std::vector<std::array<Vec2, 3>> tri_uv;
    for (size_t t = 0; t < s.tris.size(); ++t)
      if (!regions.count(s.tri_face[t]) || held.count(static_cast<int>(t))) {
        tris.push_back(s.tris[t]);
        tri_face.push_back(s.tri_face[t]);
        tri_uv.push_back(s.tri_uv[t]);
      }
    for (const auto& [f, list] : regions)
      for (const Region& reg : list) {
        const FaceMesh& fm = reg.boundary;
        std::vector<int> id(fm.num_nodes());
        for (int i = 0; i < fm.num_nodes(); ++i) {
          if (fm.global[i] >= 0) {
            id[i] = fm.global[i];
            continue;
          }
          id[i] = static_cast<int>(r.xyz.size());
          r.xyz.push_back(fm.s[i].p);
          r.node_dim.push_back(2);
          r.node_entity.push_back(f);
        }
        for (const auto& t : fm.tris) {
          std::array<int, 3> gt{id[t[0]], id[t[1]], id[t[2]]};
          std::array<Vec2, 3> uv{fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]]};
          if (gt[0] == gt[1] || gt[1] == gt[2] || gt[0] == gt[2]) continue;  // on a pole
          if (reg.flip) std::swap(gt[1], gt[2]), std::swap(uv[1], uv[2]);
          fresh.push_back(static_cast<int>(tris.size()));
          tris.push_back(gt);
          tri_face.push_back(f);
          tri_uv.push_back(uv);
        }
      }
    // Triangles by face, in their order; unused nodes dropped, the others in their order.
    std::vector<int> order(tris.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return tri_face[a] < tri_face[b]; });
    std::vector<int> used(r.xyz.size(), -1);
    for (const auto& t : tris)
      for (int n : t) used[n] = 0;
    SurfaceMesh m;
    m.failures = r.failures;
    m.stats = r.stats;
    for (size_t n = 0; n < used.size(); ++n)
      if (used[n] == 0) {
        used[n] = static_cast<int>(m.xyz.size());
        m.xyz.push_back(r.xyz[n]);
        m.node_dim.push_back(r.node_dim[n]);
        m.node_entity.push_back(r.node_entity[n]);
      }
    std::vector<char> is_fresh(tris.size(), 0);
    for (int t : fresh) is_fresh[t] = 1;
    std::vector<char> fresh_sorted;
    for (int t : order) {
      m.tris.push_back({used[tris[t][0]], used[tris[t][1]], used[tris[t][2]]});
      m.tri_face.push_back(tri_face[t]);
      m.tri_uv.push_back(tri_uv[t]);
      fresh_sorted.push_back(is_fresh[t]);
    }
    // Two faces meshed again on either side of a thin corner may both join
    // the same two curve nodes by an inner edge (an edge used four times).
    size_t open_now = open_edges(m);
    if (open_now > open_before) {
      flip_shared_inner_edges(m);
      open_now = open_edges(m);
    }
    if (open_now > open_before) {
      // Faces whose new triangles leave an edge open or used more than twice
      // keep theirs next round.
      std::unordered_map<uint64_t, std::vector<int>> uses;
      for (size_t t = 0; t < m.tris.size(); ++t)
        for (int k = 0; k < 3; ++k) uses[edge_key(m.tris[t][k], m.tris[t][(k + 1) % 3])].push_back(static_cast<int>(t));
      bool blamed = false;
      for (const auto& [e, u] : uses)
        if (u.size() != 2)
          for (int t : u)
            if (fresh_sorted[t]) blamed = kept.insert(m.tri_face[t]).second || blamed;
      if (!blamed) return out;
      continue;
    }
    // New triangles that cross others or turn against their surface.
    std::vector<int> wrong;
    const SelfIntersections hits = find_self_intersections(m, size_t(1) << 16);
    if (more_crossings(hits.pairs))
      for (const auto& [a, b] : hits.kept)
        for (int t : {a, b})
          if (fresh_sorted[t]) wrong.push_back(t);
    const size_t crossing_wrong = wrong.size();
    for (size_t t = 0; t < m.tris.size(); ++t)
      if (fresh_sorted[t] && inverted_triangle(m, g, t)) wrong.push_back(static_cast<int>(t));
    bool blamed = false;
    if (!wrong.empty()) {
      // Where two surfaces graze (a fin's root section lying on a fuselage's
      // top), each side meshed on its own crosses the other within its
      // chords. The old triangles (which crossed nothing) around each wrong
      // new one are held next round, the rest of the face meshed again
      // around them, and the junctions through them keep their nodes; in the
      // last rounds, or where nothing more is held, the face keeps all its
      // triangles.
      const bool hold = round + 2 < kRounds;
      for (size_t i = 0; i < wrong.size(); ++i) {
        const int t = wrong[i], f = m.tri_face[t];
        // The new triangle's box, grown by a quarter of its size: the old
        // ones are chords of the same surface, nearer to it or farther.
        Eigen::AlignedBox3d zone;
        for (int n : m.tris[t]) zone.extend(m.xyz[n]);
        const Eigen::Vector3d margin = Eigen::Vector3d::Constant(0.25 * zone.diagonal().norm());
        zone = Eigen::AlignedBox3d(zone.min() - margin, zone.max() + margin);
        auto& boxes = old_boxes[f];
        if (boxes.empty())
          for (int old : tris_of[f]) {
            boxes.emplace_back();
            for (int n : s.tris[old]) boxes.back().extend(s.xyz[n]);
          }
        std::vector<int> near;
        for (size_t j = 0; j < boxes.size(); ++j)
          if (zone.intersects(boxes[j])) near.push_back(tris_of[f][j]);
        // A new triangle turned over where the old ones are too (a
        // trailing edge thinner than the elements) is no worse than they.
        auto turned = [&](int old) { return inverted_triangle(s, g, static_cast<size_t>(old)); };
        if (i >= crossing_wrong && std::any_of(near.begin(), near.end(), turned)) continue;
        if (!hold || kept.count(f) || near.empty()) {
          blamed = kept.insert(f).second || blamed;
          continue;
        }
        for (int old : near) blamed = held.insert(old).second || blamed;
      }
      for (size_t k = 0; k < chains.size(); ++k)
        for (size_t j = 0; j + 1 < chains[k].nodes.size() && !frozen.count(k); ++j)
          for (int t : topo.edge_tris.at(edge_key(chains[k].nodes[j], chains[k].nodes[j + 1])))
            if (held.count(t)) frozen.insert(k);
    }
    // Nothing more to hold or keep: new triangles turned over alone are
    // taken as they are (the old ones were no better), crossings never.
    if (blamed) continue;
    if (more_crossings(hits.pairs)) return out;
    // The junction as it ends: each chain's new nodes or its old ones.
    std::vector<std::array<int, 2>> ends;
    for (size_t k = 0; k < chains.size(); ++k) {
      const Chain& c = chains[k];
      const bool substituted = c.usable && !frozen.count(k) && !kept.count(c.fa) && !kept.count(c.fb);
      std::vector<int> path = c.nodes;
      if (substituted) {
        path = {c.nodes.front()};
        path.insert(path.end(), c.id.begin(), c.id.end());
        path.push_back(c.nodes.back());
        out.junction_nodes += static_cast<int>(c.id.size());
      }
      for (size_t j = 0; j + 1 < path.size(); ++j)
        if (used[path[j]] >= 0 && used[path[j + 1]] >= 0) ends.push_back({used[path[j]], used[path[j + 1]]});
    }
    out.faces_remeshed = static_cast<int>(regions.size());
    out.faces_kept = static_cast<int>(kept.size());
    s = std::move(m);
    u.junction = std::move(ends);
    const JunctionSliverResult thin = remove_junction_slivers(s, g, h, u.junction, hits.pairs);
    out.thin_collapsed = thin.collapsed;
    out.thin_flipped = thin.flipped;
    out.thin_pinched = thin.pinched;
    measure_junction(s, g, u, 1e4 * tol);  // 1e-9 of the diagonal, as unite_meshes()
    return out;
  }
  return out;
}

}  // namespace sizemesh
