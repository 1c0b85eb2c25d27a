// The base-element search (paper 4.2): the walk-through from a start triangle, and the brute-force scan.
#include <cstdint>

#include "sizing/size_query_interpolate.h"

namespace sizemesh {

using size_query_detail::interpolate;
using size_query_detail::interpolate_on_edges;
using size_query_detail::kDegenerate;
using size_query_detail::lerp;
using size_query_detail::orient;
using size_query_detail::within_extent;

namespace {

// Squared uv length of edge k (corner k+1 to corner k+2).
inline double edge_length2(const SizeQuery::Tri& T, int k) {
  return (T.uv[(k + 2) % 3] - T.uv[(k + 1) % 3]).squaredNorm();
}

constexpr int kGreedySteps = 16;  // walk steps that choose the exit edge greedily

}  // namespace

// The walk-through (Shan et al. 2008, as the paper adopts): from the start
// triangle, cross an edge the point lies beyond, never the entry edge. With two
// such edges the first steps take the one the point is farthest beyond; later
// steps toss a deterministic coin (remembering stochastic walk), which breaks
// the cycles a visibility walk can fall into in non-Delaunay triangulations.
// The step limit ends a walk still cycling (folded patches) in the scan.
SizeQuery::Hit SizeQuery::walk(const Face& f, const Vec2& p, int t, QueryStats& st) const {
  const Tri* tris = f.tris.data();
  const double px = p.x(), py = p.y();
  uint32_t coin = 0x9e3779b9u ^ static_cast<uint32_t>(t);
  int entry = -1;
  bool forced = false;  // left a zero-area triangle without a side test: do not trust the entry edge
  for (int steps = 1;; ++steps) {
    const Tri& T = tris[t];
    const double o0 = orient(T, 0, px, py), o1 = orient(T, 1, px, py), o2 = orient(T, 2, px, py);
    unsigned beyond = (o0 < 0 ? 1u : 0u) | (o1 < 0 ? 2u : 0u) | (o2 < 0 ? 4u : 0u);
    if (entry >= 0) beyond &= ~(1u << entry);
    if (T.base & kDegenerate) {
      // A zero-area triangle claims its whole supporting line: stop only within
      // its extent, else leave by an edge the point lies beyond (any but the
      // entry when it lies on the line), and trust no entry edge afterwards.
      if (!beyond && within_extent(T, p)) {
        st.visited += steps;
        return {interpolate(T, p, o0, o1, o2), t};
      }
      if (!beyond) beyond = 7u & ~(entry >= 0 ? 1u << entry : 0u);
      forced = true;
    } else if (!beyond) {
      st.visited += steps;
      return {interpolate(T, p, o0, o1, o2), t};
    }
    int k = __builtin_ctz(beyond);
    if (beyond & (beyond - 1)) {
      const int a = k, b = __builtin_ctz(beyond & (beyond - 1));
      if (steps <= kGreedySteps) {
        // The edge the point is farthest beyond (signed distance o_k / |edge k|),
        // which heads straight across anisotropic patches.
        const double oa = a == 0 ? o0 : o1, ob = b == 1 ? o1 : o2;
        k = oa * oa * edge_length2(T, b) >= ob * ob * edge_length2(T, a) ? a : b;
      } else {
        // Past that, a deterministic coin: breaks the cycles a greedy walk can fall into.
        coin ^= coin << 13;
        coin ^= coin >> 17;
        coin ^= coin << 5;
        k = (coin & 1) ? b : a;
      }
      const int other = k == a ? b : a;
      if (T.adj[k] < 0 && T.adj[other] >= 0) k = other;  // prefer the edge that leads on
    }
    const int n = T.adj[k];
    if (n < 0) {
      st.visited += steps;
      return clamp_to_boundary(f, p, t, k, st);
    }
    if (steps >= f.step_limit) {
      st.visited += steps;
      ++st.fallbacks;
      return brute_force(f, p, st);
    }
    entry = forced ? -1 : T.back[k];
    forced = false;
    t = n;
  }
}

// Brute force: the first non-degenerate triangle containing the point, else a
// degenerate one on whose line it lies, else the nearest point of the domain.
SizeQuery::Hit SizeQuery::brute_force(const Face& f, const Vec2& p, QueryStats& st) const {
  const int nt = static_cast<int>(f.tris.size());
  st.visited += nt;
  int degenerate = -1;
  for (int t = 0; t < nt; ++t) {
    const Tri& T = f.tris[t];
    const double o0 = orient(T, 0, p.x(), p.y()), o1 = orient(T, 1, p.x(), p.y()), o2 = orient(T, 2, p.x(), p.y());
    if (o0 < 0 || o1 < 0 || o2 < 0) continue;
    if (T.base & kDegenerate) {
      if (degenerate < 0 && within_extent(T, p)) degenerate = t;
      continue;
    }
    return {interpolate(T, p, o0, o1, o2), t};
  }
  if (degenerate >= 0) return {interpolate_on_edges(f.tris[degenerate], p), degenerate};
  // Outside every triangle: the nearest point on any triangle edge.
  ++st.outside;
  double best = std::numeric_limits<double>::infinity(), h = f.tris[0].h[0];
  int best_t = 0;
  for (int t = 0; t < nt; ++t) {
    const Tri& T = f.tris[t];
    for (int k = 0; k < 3; ++k) {
      const int a = (k + 1) % 3, b = (k + 2) % 3;
      double s, d2;
      project_segment(T.uv[a], T.uv[b], p, s, d2);
      if (d2 < best) {
        best = d2;
        best_t = t;
        h = lerp(T.h[a], T.h[b], s);
      }
    }
  }
  return {h, best_t};
}

}  // namespace sizemesh
