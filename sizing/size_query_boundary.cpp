// A walk blocked by the patch boundary: the point clamped to the nearest boundary point, or the obstacle gone around.
#include <algorithm>
#include <limits>

#include "sizing/size_query_interpolate.h"

namespace sizemesh {

using size_query_detail::BEdge;
using size_query_detail::interpolate;
using size_query_detail::kDegenerate;
using size_query_detail::lerp;
using size_query_detail::orient;
using size_query_detail::within_extent;

// The point lies beyond boundary edge k of triangle t. Follow the boundary
// chain to a point q nearer to it than the neighbouring boundary edges (inside
// an edge, or a corner). When moreover the distance d to q is at most half the
// clearance of q's edge (no other boundary edge comes nearer than that), q is
// the nearest boundary point of the whole domain; if the point also lies beyond
// the edge(s) at q it is outside the domain and takes the size at q, linear
// along the boundary, never extrapolated. This covers chord sagitta, trimming
// tolerance and round-off. Anything else (a point inside a non-convex domain
// behind a notch, slot or hole, or far outside) goes to the brute-force scan,
// which is exact.
SizeQuery::Hit SizeQuery::clamp_to_boundary(const Face& f, const Vec2& p, int t, int k, QueryStats& st) const {
  const Tri* tris = f.tris.data();
  const BEdge* be = f.bedges.data();
  auto ends = [&](int e, Vec2& P, Vec2& Q) {
    P = tris[be[e].t].uv[(be[e].k + 1) % 3];
    Q = tris[be[e].t].uv[(be[e].k + 2) % 3];
  };
  auto dist2 = [&](int e, double& s) {
    Vec2 P, Q;
    ends(e, P, Q);
    double d2;
    project_segment(P, Q, p, s, d2);
    return d2;
  };
  auto beyond = [&](int e) { return orient(tris[be[e].t], be[e].k, p.x(), p.y()) < 0; };
  auto fallback = [&](int visited) {
    st.visited += visited;
    return go_around(f, p, t, st);
  };
  int e = f.bslot[3 * t + k];
  int visited = 0;
  while (++visited <= f.step_limit) {
    double s;
    const double d2 = dist2(e, s);
    const int prev = be[e].prev, next = be[e].next;
    if (prev < 0 || next < 0) break;
    double sp, sn;
    const double dp2 = dist2(prev, sp), dn2 = dist2(next, sn);
    if (s > 0 && s < 1) {
      // Inside edge e: move on if a neighbour is nearer.
      if (dp2 < d2) {
        e = prev;
        continue;
      }
      if (dn2 < d2) {
        e = next;
        continue;
      }
      if (!((beyond(e) || d2 == 0) && 4 * d2 <= be[e].clearance * be[e].clearance)) break;
      st.visited += visited;
      if (d2 > 0) ++st.outside;  // on the boundary itself it is not outside
      const Tri& T = tris[be[e].t];
      return {lerp(T.h[(be[e].k + 1) % 3], T.h[(be[e].k + 2) % 3], s), be[e].t};
    }
    // Nearest at an end of e: go on along the boundary past that end, or stop at
    // the corner V between e_in and e_out when both are nearest at V.
    if (s <= 0 && sp < 1) {
      e = prev;
      continue;
    }
    if (s >= 1 && sn > 0) {
      e = next;
      continue;
    }
    const int e_in = s <= 0 ? prev : e, e_out = s <= 0 ? e : next;
    // Corner V: nearer than both edges at it. Check the edges one further out.
    const int before = be[e_in].prev, after = be[e_out].next;
    if (before < 0 || after < 0) break;
    double sb, sa;
    if (dist2(before, sb) < d2) {
      e = before;
      continue;
    }
    if (dist2(after, sa) < d2) {
      e = after;
      continue;
    }
    if (!((beyond(e_in) || beyond(e_out) || d2 == 0) && 4 * d2 <= std::min(be[e_in].clearance, be[e_out].clearance) *
                                                           std::min(be[e_in].clearance, be[e_out].clearance)))
      break;
    st.visited += visited;
    if (d2 > 0) ++st.outside;
    const Tri& T = tris[be[e_out].t];
    return {T.h[(be[e_out].k + 1) % 3], be[e_out].t};
  }
  return fallback(visited);
}

// Going around an obstacle (Bug2): walk straight along the segment m from S,
// the centroid of triangle t0, to the point. Blocked by a boundary edge at H,
// follow the boundary chain (domain on the left) and leave it at the first edge
// that crosses m nearer the point than H with the point on its inner side.
// Back at the blocking edge without leaving, the point cannot be reached: it is
// outside the domain (in a hole or beyond the outer loop), and the nearest
// point of the domain lies on the loop just followed. Only adjacency and the
// boundary links are used; a step budget ends in the brute-force scan.
SizeQuery::Hit SizeQuery::go_around(const Face& f, const Vec2& p, int t0, QueryStats& st) const {
  const Tri* tris = f.tris.data();
  const BEdge* be = f.bedges.data();
  const Tri& T0 = tris[t0];
  const Vec2 S = (T0.uv[0] + T0.uv[1] + T0.uv[2]) / 3;
  auto side = [&](const Vec2& v) { return orient(S, p, v); };  // > 0: left of m
  const int budget = 4 * (static_cast<int>(f.tris.size()) + static_cast<int>(f.bedges.size())) + 64;
  const double progress = 1e-12 * (f.hi - f.lo).norm();
  int visited = 0, t = t0, entry = -1;
  double dH = std::numeric_limits<double>::infinity();
  auto give_up = [&]() {
    st.visited += visited;
    ++st.fallbacks;
    return brute_force(f, p, st);
  };
  for (;;) {
    if (++visited > budget) return give_up();
    const Tri& T = tris[t];
    const double o[3] = {orient(T, 0, p.x(), p.y()), orient(T, 1, p.x(), p.y()), orient(T, 2, p.x(), p.y())};
    if (o[0] >= 0 && o[1] >= 0 && o[2] >= 0 && (!(T.base & kDegenerate) || within_extent(T, p))) {
      st.visited += visited;
      return {interpolate(T, p, o[0], o[1], o[2]), t};
    }
    // Exit edge of m: the edge other than the entry whose ends straddle m.
    int k = -1;
    if (entry >= 0) {
      const int c = entry;
      const double sv = side(T.uv[c]), s1 = side(T.uv[(c + 1) % 3]);
      k = (sv > 0) == (s1 > 0) && sv != 0 ? (c + 1) % 3 : (c + 2) % 3;
    } else {
      for (int j = 0; j < 3 && k < 0; ++j) {
        const double a = side(T.uv[(j + 1) % 3]), b = side(T.uv[(j + 2) % 3]);
        if (o[j] < 0 && ((a <= 0 && b >= 0) || (a >= 0 && b <= 0))) k = j;
      }
    }
    if (k < 0 || o[k] >= 0) {  // round-off: leave by any edge the point lies beyond
      k = -1;
      for (int j = 0; j < 3; ++j)
        if (j != entry && o[j] < 0 && (k < 0 || o[j] < o[k])) k = j;
      if (k < 0) return give_up();
    }
    if (T.adj[k] >= 0) {
      entry = T.back[k];
      t = T.adj[k];
      continue;
    }
    // Blocked at H on boundary edge (t, k): follow the boundary.
    const int hit = f.bslot[3 * t + k];
    {
      const Vec2 &P = T.uv[(k + 1) % 3], &Q = T.uv[(k + 2) % 3];
      const double a = side(P), b = side(Q);
      const Vec2 H = a != b ? Vec2(P + a / (a - b) * (Q - P)) : P;
      dH = std::min(dH, (H - p).norm());
    }
    int e = hit, best_e = hit;
    double best_d2 = std::numeric_limits<double>::infinity(), best_s = 0;
    bool left = false;
    for (;;) {
      const Tri& E = tris[be[e].t];
      const Vec2 &P = E.uv[(be[e].k + 1) % 3], &Q = E.uv[(be[e].k + 2) % 3];
      double s, d2;
      project_segment(P, Q, p, s, d2);
      if (d2 < best_d2) {
        best_d2 = d2;
        best_e = e;
        best_s = s;
      }
      if (e != hit && orient(E, be[e].k, p.x(), p.y()) > 0) {
        const double a = side(P), b = side(Q);
        if ((a <= 0 && b >= 0) || (a >= 0 && b <= 0)) {
          const Vec2 X = a != b ? Vec2(P + a / (a - b) * (Q - P)) : P;
          // Leave only with real progress toward the point: a point lying on a
          // boundary edge up to round-off would otherwise re-enter forever.
          if ((X - S).dot(p - S) >= 0 && (X - p).norm() < dH - progress) {
            t = be[e].t;
            entry = be[e].k;
            left = true;
            break;
          }
        }
      }
      e = be[e].next;
      if (e < 0 || ++visited > budget) return give_up();
      if (e == hit) break;
    }
    if (left) continue;
    // Unreachable: outside; the nearest point of the loop.
    st.visited += visited;
    ++st.outside;
    const Tri& B = tris[be[best_e].t];
    return {lerp(B.h[(be[best_e].k + 1) % 3], B.h[(be[best_e].k + 2) % 3], best_s), be[best_e].t};
  }
}

}  // namespace sizemesh
