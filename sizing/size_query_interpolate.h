// Interpolation of the size inside a base triangle of the size query, and the zero-area triangle test.
//
// Internal to the size query (sizing/size_query*.cpp): the walk, the
// boundary clamp and the brute-force scan answer with these.
#pragma once

#include <algorithm>
#include <limits>

#include "core/predicates.h"
#include "sizing/size_query_face.h"

namespace sizemesh::size_query_detail {

inline double lerp(double a, double b, double s) { return (1 - s) * a + s * b; }

// Size on the nearest edge of a triangle (degenerate triangles: the point lies on
// their line; ties go to the shorter edge so a vertex lying on a longer edge keeps
// its own size and the answer matches the neighbours).
inline double interpolate_on_edges(const SizeQuery::Tri& T, const Vec2& p) {
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

}  // namespace sizemesh::size_query_detail
