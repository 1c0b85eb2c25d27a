// Size query construction (paper 4.2): per-triangle walk records with
// neighbours and canonical edge ends, a grid of start triangles over each
// face's uv box, and the linked boundary chain used to clamp points outside.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/predicates.h"
#include "sizing/size_query_face.h"

namespace sizemesh::size_query_detail {

namespace {

void build_start_grid(SizeQuery::Face& f) {
  const int nt = static_cast<int>(f.tris.size());
  const Vec2 span = (f.hi - f.lo).cwiseMax(Vec2::Constant(1e-300));
  // About four cells per triangle, cells shaped like the patch's uv box.
  const double cells = std::max(1.0, 4.0 * nt);
  const double ratio = span.x() / span.y();
  f.nx = static_cast<int>(std::clamp(std::round(std::sqrt(cells * ratio)), 1.0, 4096.0));
  f.ny = static_cast<int>(std::clamp(std::round(cells / f.nx), 1.0, 4096.0));
  f.grid_lo = f.lo;
  f.inv_du = f.nx / span.x();
  f.inv_dv = f.ny / span.y();
  f.cell_tri.assign(static_cast<size_t>(f.nx) * f.ny, -1);
  const double du = span.x() / f.nx, dv = span.y() / f.ny;
  for (int t = 0; t < nt; ++t) {
    const SizeQuery::Tri& T = f.tris[t];
    if (T.base & kDegenerate) continue;
    Vec2 lo = T.uv[0].cwiseMin(T.uv[1]).cwiseMin(T.uv[2]), hi = T.uv[0].cwiseMax(T.uv[1]).cwiseMax(T.uv[2]);
    const int i0 = std::max(0, static_cast<int>(std::ceil((lo.x() - f.lo.x()) / du - 0.5)));
    const int i1 = std::min(f.nx - 1, static_cast<int>(std::floor((hi.x() - f.lo.x()) / du - 0.5)));
    const int j0 = std::max(0, static_cast<int>(std::ceil((lo.y() - f.lo.y()) / dv - 0.5)));
    const int j1 = std::min(f.ny - 1, static_cast<int>(std::floor((hi.y() - f.lo.y()) / dv - 0.5)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        int& cell = f.cell_tri[static_cast<size_t>(j) * f.nx + i];
        if (cell >= 0) continue;
        const double px = f.lo.x() + (i + 0.5) * du, py = f.lo.y() + (j + 0.5) * dv;
        if (orient(T, 0, px, py) >= 0 && orient(T, 1, px, py) >= 0 && orient(T, 2, px, py) >= 0) cell = t;
      }
  }
  // Cells whose centre is outside the domain take a neighbouring cell's triangle
  // (breadth-first from the covered cells).
  std::vector<int> queue;
  for (int c = 0; c < static_cast<int>(f.cell_tri.size()); ++c)
    if (f.cell_tri[c] >= 0) queue.push_back(c);
  if (queue.empty()) {
    std::fill(f.cell_tri.begin(), f.cell_tri.end(), 0);
    return;
  }
  for (size_t q = 0; q < queue.size(); ++q) {
    const int c = queue[q], i = c % f.nx, j = c / f.nx;
    const int nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
    for (const auto& n : nb) {
      if (n[0] < 0 || n[0] >= f.nx || n[1] < 0 || n[1] >= f.ny) continue;
      int& cell = f.cell_tri[static_cast<size_t>(n[1]) * f.nx + n[0]];
      if (cell >= 0) continue;
      cell = f.cell_tri[c];
      queue.push_back(n[1] * f.nx + n[0]);
    }
  }
}

// Links the boundary edges of a patch (rotating around each end through the
// triangle fan) and computes their clearances.
void build_boundary(SizeQuery::Face& f, const FacePatch& patch) {
  const int nt = static_cast<int>(f.tris.size());
  f.bslot.assign(3 * static_cast<size_t>(nt), -1);
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      if (f.tris[t].adj[k] < 0) {
        f.bslot[3 * t + k] = static_cast<int>(f.bedges.size());
        BEdge e;
        e.t = t;
        e.k = k;
        f.bedges.push_back(e);
      }
  const auto& tv = patch.tris;
  auto corner_of = [&](int t, int v) {
    for (int c = 0; c < 3; ++c)
      if (tv[t][c] == v) return c;
    return -1;
  };
  // Around vertex v = corner c of triangle t, forward (leaving by the edge from v)
  // or backward (by the edge into v), until an edge with no neighbour: its slot
  // 3 t + k, or -1 when the fan is broken.
  auto rotate = [&](int t, int c, bool forward) {
    const int v = tv[t][c];
    int from = -1;
    for (int steps = 0; steps <= nt; ++steps) {
      // The two edges at v are opposite corners c+1 and c+2; leave by the one not leading back.
      int j = forward ? (c + 2) % 3 : (c + 1) % 3;
      if (from >= 0 && f.tris[t].adj[j] == from) j = forward ? (c + 1) % 3 : (c + 2) % 3;
      const int n = f.tris[t].adj[j];
      if (n < 0) return 3 * t + j;
      from = t;
      t = n;
      c = corner_of(t, v);
      if (c < 0) return -1;
    }
    return -1;
  };
  for (BEdge& e : f.bedges) {
    const int a = tv[e.t][(e.k + 1) % 3], b = tv[e.t][(e.k + 2) % 3];
    // Next: the boundary edge leaving b; previous: the one arriving at a.
    int slot = rotate(e.t, (e.k + 2) % 3, true);
    if (slot >= 0 && tv[slot / 3][(slot % 3 + 1) % 3] == b) e.next = f.bslot[slot];
    slot = rotate(e.t, (e.k + 1) % 3, false);
    if (slot >= 0 && tv[slot / 3][(slot % 3 + 2) % 3] == a) e.prev = f.bslot[slot];
  }
  // Clearances, by a sweep in u; beyond the longest boundary edge they are not needed.
  const int nb = static_cast<int>(f.bedges.size());
  std::vector<std::array<Vec2, 2>> seg(nb);
  double cap = 0;
  for (int i = 0; i < nb; ++i) {
    const SizeQuery::Tri& T = f.tris[f.bedges[i].t];
    seg[i] = {T.uv[(f.bedges[i].k + 1) % 3], T.uv[(f.bedges[i].k + 2) % 3]};
    cap = std::max(cap, (seg[i][1] - seg[i][0]).norm());
  }
  for (BEdge& e : f.bedges) e.clearance = cap;
  std::vector<int> order(nb);
  for (int i = 0; i < nb; ++i) order[i] = i;
  auto umin = [&](int i) { return std::min(seg[i][0].x(), seg[i][1].x()); };
  auto umax = [&](int i) { return std::max(seg[i][0].x(), seg[i][1].x()); };
  std::sort(order.begin(), order.end(), [&](int x, int y) { return umin(x) < umin(y); });
  for (int a = 0; a < nb; ++a) {
    const int i = order[a];
    for (int b = a + 1; b < nb && umin(order[b]) <= umax(i) + cap; ++b) {
      const int j = order[b];
      BEdge &ei = f.bedges[i], &ej = f.bedges[j];
      const bool neighbours = ei.prev == j || ei.next == j;
      const bool neighbours_j = ej.prev == i || ej.next == i;
      if (neighbours && neighbours_j) continue;
      const double d = segment_distance(seg[i][0], seg[i][1], seg[j][0], seg[j][1]);
      if (!neighbours) ei.clearance = std::min(ei.clearance, d);
      if (!neighbours_j) ej.clearance = std::min(ej.clearance, d);
    }
  }
}

}  // namespace

SizeQuery::Face build_face(const FacePatch& patch, int id, const std::vector<double>& h, double period_u,
                           double period_v) {
  SizeQuery::Face f;
  f.id = id;
  f.period_u = period_u > 0 ? period_u : 0;
  f.period_v = period_v > 0 ? period_v : 0;
  const int nt = static_cast<int>(patch.tris.size());
  if (nt == 0 || patch.uv.empty()) return f;
  f.lo = f.hi = patch.uv[0];
  for (const Vec2& uv : patch.uv) {
    f.lo = f.lo.cwiseMin(uv);
    f.hi = f.hi.cwiseMax(uv);
  }
  f.tris.resize(nt);
  for (int t = 0; t < nt; ++t) {
    SizeQuery::Tri& T = f.tris[t];
    const auto& v = patch.tris[t];
    for (int k = 0; k < 3; ++k) {
      T.uv[k] = patch.uv[v[k]];
      const int g = patch.vertex[v[k]];
      if (g < 0 || g >= static_cast<int>(h.size()))
        throw Error("size query: face " + std::to_string(id) + " uses a background vertex with no size");
      T.h[k] = h[g];
      T.adj[k] = patch.adj.empty() ? -1 : patch.adj[t][k];
      T.back[k] = -1;
      // Canonical end of edge k: the lower local vertex id of corners k+1, k+2.
      if (v[(k + 2) % 3] < v[(k + 1) % 3]) T.base |= static_cast<uint8_t>(1u << k);
    }
    const Vec2 e1 = T.uv[1] - T.uv[0], e2 = T.uv[2] - T.uv[0], e3 = T.uv[2] - T.uv[1];
    const double area2 = e1.x() * e2.y() - e1.y() * e2.x();
    const double lmax2 = std::max({e1.squaredNorm(), e2.squaredNorm(), e3.squaredNorm()});
    if (!(area2 > 1e-12 * lmax2)) T.base |= kDegenerate;
  }
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const int n = f.tris[t].adj[k];
      if (n < 0 || n >= nt) {
        f.tris[t].adj[k] = -1;
        continue;
      }
      for (int j = 0; j < 3; ++j)
        if (f.tris[n].adj[j] == t) f.tris[t].back[k] = static_cast<int8_t>(j);
      if (f.tris[t].back[k] < 0) f.tris[t].adj[k] = -1;  // one-sided adjacency: treat as boundary
    }
  // A straight walk crosses each triangle at most once; in a patch whose
  // triangles are long and thin in uv (well shaped in space on a stretched
  // parametrisation) it may cross most of them.
  f.step_limit = 64 + nt;
  build_start_grid(f);
  build_boundary(f, patch);
  return f;
}

}  // namespace sizemesh::size_query_detail
