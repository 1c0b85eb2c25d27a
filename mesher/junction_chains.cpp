// The junction's topology read from the mesh, its chains from corner to corner, and their resampling.
#include "mesher/junction_chains.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "background/background_mesh.h"
#include "mesher/snap.h"

namespace sizemesh::cut_faces_detail {

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

Topology::Topology(const SurfaceMesh& s, const Geometry& g, const std::vector<std::array<int, 2>>& junction) {
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

void resample(Chain& c, const SurfaceMesh& s, const Topology& topo, const Geometry& g, const SizeField& h,
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

}  // namespace sizemesh::cut_faces_detail
