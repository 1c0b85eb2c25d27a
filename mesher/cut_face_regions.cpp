// A cut face's regions: its triangles' boundary walked into loops in uv, the junction's new nodes in place.
#include "mesher/cut_face_regions.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_set>

#include "background/background_mesh.h"

namespace sizemesh::cut_faces_detail {
namespace {

// The edge from a to b, told apart from the edge from b to a.
uint64_t directed_key(int a, int b) { return (uint64_t(uint32_t(a)) << 32) | uint32_t(b); }

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

}  // namespace

bool same_boundary(const FaceMesh& a, const FaceMesh& b) {
  return a.face == b.face && a.global == b.global && a.pole == b.pole && a.loops == b.loops && a.uv == b.uv &&
         a.shared_xyz == b.shared_xyz && a.tris == b.tris;
}

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

}  // namespace sizemesh::cut_faces_detail
