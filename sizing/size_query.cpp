// The size query service (paper 4.2): walk-through base-element search in a
// face's uv space after Shan et al. 2008, linear interpolation in the base
// triangle, boundary clamping, and a 3D nearest-triangle query for at_xyz.
// Construction is in size_query_build.cpp, the counters in size_query_stats.cpp.
#include "sizing/size_query.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "geometry/predicates.h"
#include "geometry/triangle_bvh.h"
#include "sizing/size_query_face.h"

namespace sizemesh {

using size_query_detail::BEdge;
using size_query_detail::build_face;
using size_query_detail::kDegenerate;
using size_query_detail::kOwnedSlots;
using size_query_detail::orient;

namespace {

// Squared uv length of edge k (corner k+1 to corner k+2).
inline double edge_length2(const SizeQuery::Tri& T, int k) {
  return (T.uv[(k + 2) % 3] - T.uv[(k + 1) % 3]).squaredNorm();
}

constexpr int kGreedySteps = 16;  // walk steps that choose the exit edge greedily

inline double lerp(double a, double b, double s) { return (1 - s) * a + s * b; }

// Size on the nearest edge of a triangle (degenerate triangles: the point lies on
// their line; ties go to the shorter edge so a vertex lying on a longer edge keeps
// its own size and the answer matches the neighbours).
double interpolate_on_edges(const SizeQuery::Tri& T, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity(), best_len = 0, h = T.h[0];
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    double s, d2;
    project_segment(T.uv[a], T.uv[b], p, s, d2);
    const double len = (T.uv[b] - T.uv[a]).squaredNorm();
    const double tol = 1e-24 * std::max(len, best_len);
    if (d2 < best - tol || (d2 <= best + tol && len < best_len)) {
      best = d2;
      best_len = len;
      h = lerp(T.h[a], T.h[b], s);
    }
  }
  return h;
}

// Linear (barycentric) interpolation in the base triangle from the edge
// orientations o_k = 2 area * lambda_k. Negative o_k (round-off, folds) are
// clamped to 0, so the answer is always a convex combination of the corners.
inline double interpolate(const SizeQuery::Tri& T, const Vec2& p, double o0, double o1, double o2) {
  o0 = std::max(o0, 0.0);
  o1 = std::max(o1, 0.0);
  o2 = std::max(o2, 0.0);
  const double s = o0 + o1 + o2;
  if (!(T.base & kDegenerate) && s > 0) return (o0 * T.h[0] + o1 * T.h[1] + o2 * T.h[2]) / s;
  return interpolate_on_edges(T, p);
}

// For zero-area triangles: the point lies within the corners' bounding box.
inline bool within_extent(const SizeQuery::Tri& T, const Vec2& p) {
  const Vec2 lo = T.uv[0].cwiseMin(T.uv[1]).cwiseMin(T.uv[2]), hi = T.uv[0].cwiseMax(T.uv[1]).cwiseMax(T.uv[2]);
  return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
}

// Wraps x by period P to the position nearest the range [lo, hi].
double wrap_periodic(double x, double lo, double hi, double P) {
  double y = lo + std::fmod(x - lo, P);
  if (y < lo) y += P;
  const double above = y > hi ? y - hi : 0.0;
  const double below = lo - (y - P);
  return below < above ? y - P : y;
}

[[noreturn]] void throw_bad_face(int face, int num_faces) {
  throw Error("size query: face " + std::to_string(face) + " does not exist (the background mesh has " +
              std::to_string(num_faces) + " faces)");
}

[[noreturn]] void throw_empty_face(int face) {
  throw Error("size query: face " + std::to_string(face) +
              " has no background triangles, so no size can be looked up in its uv space");
}

[[noreturn]] void throw_bad_uv(int face) {
  throw Error("size query: a non-finite uv was asked on face " + std::to_string(face));
}

}  // namespace

SizeQuery::SizeQuery(const BackgroundMesh& bg, std::vector<double> h, std::vector<double> period_u,
                     std::vector<double> period_v)
    : bvh_(std::make_unique<TriangleBVH>(bg.xyz, bg.tris)), slots_(std::make_unique<StatSlot[]>(kOwnedSlots + 1)) {
  if (h.size() != bg.xyz.size())
    throw Error("size query: " + std::to_string(h.size()) + " sizes given for " + std::to_string(bg.xyz.size()) +
                " background vertices");
  const int nf = static_cast<int>(bg.patches.size());
  faces_.reserve(nf);
  for (int i = 0; i < nf; ++i) {
    const double pu = i < static_cast<int>(period_u.size()) ? period_u[i] : 0;
    const double pv = i < static_cast<int>(period_v.size()) ? period_v[i] : 0;
    faces_.push_back(build_face(bg.patches[i], i + 1, h, pu, pv));
  }
  tri_h_.resize(bg.tris.size());
  for (size_t t = 0; t < bg.tris.size(); ++t)
    for (int k = 0; k < 3; ++k) tri_h_[t][k] = h[bg.tris[t][k]];
}

SizeQuery::~SizeQuery() = default;
SizeQuery::SizeQuery(SizeQuery&&) noexcept = default;
SizeQuery& SizeQuery::operator=(SizeQuery&&) noexcept = default;

int SizeQuery::num_faces() const { return static_cast<int>(faces_.size()); }

int SizeQuery::num_triangles(int face) const {
  if (face < 1 || face > num_faces()) return 0;
  return static_cast<int>(faces_[face - 1].tris.size());
}

const SizeQuery::Face& SizeQuery::face_data(int face) const {
  if (face < 1 || face > num_faces()) throw_bad_face(face, num_faces());
  const Face& f = faces_[face - 1];
  if (f.tris.empty()) throw_empty_face(face);
  return f;
}

// ---------------------------------------------------------------------------
// Queries in uv (paper 4.2)

SizeQuery::Hit SizeQuery::locate(int face, const Vec2& uv, int hint, QueryStats* stats) const {
  if (surface_ && face >= 1 && face <= num_faces() && faces_[face - 1].tris.empty()) {
    if (stats) ++stats->queries;
    return {at_xyz(surface_(face, uv)), -1};  // no uv triangulation to walk: the nearest size in space
  }
  const Face& f = face_data(face);
  if (!std::isfinite(uv.x()) || !std::isfinite(uv.y())) throw_bad_uv(face);
  // Periodic faces: bring the point into the patch's uv range (across the seam).
  Vec2 p = uv;
  if (f.period_u > 0 && (p.x() < f.lo.x() || p.x() > f.hi.x())) p.x() = wrap_periodic(p.x(), f.lo.x(), f.hi.x(), f.period_u);
  if (f.period_v > 0 && (p.y() < f.lo.y() || p.y() > f.hi.y())) p.y() = wrap_periodic(p.y(), f.lo.y(), f.hi.y(), f.period_v);
  // Start triangle: the hint, or the grid cell's triangle when nearer or no hint.
  const int i = static_cast<int>(std::clamp((p.x() - f.grid_lo.x()) * f.inv_du, 0.0, f.nx - 1.0));
  const int j = static_cast<int>(std::clamp((p.y() - f.grid_lo.y()) * f.inv_dv, 0.0, f.ny - 1.0));
  const int cell = f.cell_tri[static_cast<size_t>(j) * f.nx + i];
  int start = cell;
  if (static_cast<unsigned>(hint) < f.tris.size()) {
    start = hint;
    if (grid_with_hint_ && hint != cell) {
      // The nearer (uv distance to the centroid) of the hint and the cell's
      // triangle: a hint across a seam or several thin triangles away loses.
      const Tri &A = f.tris[hint], &B = f.tris[cell];
      const double da = (3 * p - A.uv[0] - A.uv[1] - A.uv[2]).squaredNorm();
      const double db = (3 * p - B.uv[0] - B.uv[1] - B.uv[2]).squaredNorm();
      if (db < da) start = cell;
    }
  }
  QueryStats st;
  st.queries = 1;
  const Hit hit = walk(f, p, start, st);
  st.max_visited = st.visited;
  if (stats) stats->add(st);
  return hit;
}

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

SizeQuery::Hit SizeQuery::locate_brute_force(int face, const Vec2& uv) const {
  const Face& f = face_data(face);
  if (!std::isfinite(uv.x()) || !std::isfinite(uv.y())) throw_bad_uv(face);
  Vec2 p = uv;
  if (f.period_u > 0 && (p.x() < f.lo.x() || p.x() > f.hi.x())) p.x() = wrap_periodic(p.x(), f.lo.x(), f.hi.x(), f.period_u);
  if (f.period_v > 0 && (p.y() < f.lo.y() || p.y() > f.hi.y())) p.y() = wrap_periodic(p.y(), f.lo.y(), f.hi.y(), f.period_v);
  QueryStats st;
  return brute_force(f, p, st);
}

double SizeQuery::at(int face, const Vec2& uv, int& hint) const {
  QueryStats st;
  const Hit hit = locate(face, uv, hint, &st);
  hint = hit.tri;
  count(st);
  return hit.h;
}

// ---------------------------------------------------------------------------
// Query in xyz: the size at the closest point of the nearest background triangle.

double SizeQuery::at_xyz(const Vec3& xyz) const {
  if (bvh_->size() == 0) throw Error("size query: the background mesh has no triangles");
  if (!xyz.allFinite()) throw Error("size query: a non-finite point was asked");
  const TriangleBVH::Closest c = bvh_->closest(xyz);
  const auto& h = tri_h_[c.tri];
  return c.weights[0] * h[0] + c.weights[1] * h[1] + c.weights[2] * h[2];
}

SizeQuery size_query_for(const Geometry& g, const BackgroundMesh& bg, std::vector<double> h) {
  std::vector<double> pu(g.num_faces()), pv(g.num_faces());
  for (int f = 1; f <= g.num_faces(); ++f) {
    pu[f - 1] = g.face_wrap_u(f);
    pv[f - 1] = g.face_wrap_v(f);
  }
  SizeQuery query(bg, std::move(h), std::move(pu), std::move(pv));
  query.set_surface([&g](int face, const Vec2& uv) { return g.eval_face(face, uv).p; });
  return query;
}

}  // namespace sizemesh
