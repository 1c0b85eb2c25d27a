// Internal to the size query (sizing/size_query*.cpp): a face's walk data,
// the per-thread counters, and the edge orientation every walk step uses.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "background/background_mesh.h"
#include "sizing/size_query.h"

namespace sizemesh {

namespace size_query_detail {

// One edge of a patch's boundary (an edge with no neighbour), directed with
// the domain on its left, linked to the boundary edges before and after it.
struct BEdge {
  int t = 0, k = 0;       // triangle and the corner the edge is opposite to
  int prev = -1, next = -1;  // boundary edges ending at its start / starting at its end, -1 if unknown
  double clearance = 0;   // uv distance to the nearest boundary edge other than itself, prev and next
};

constexpr int kOwnedSlots = 64;     // threads 0..63 own a counter slot; later threads share one more
constexpr uint8_t kDegenerate = 8;  // Tri::base bit: zero area in uv

// Orientation of p against edge k (corner k+1 -> corner k+2): twice the signed
// area, >= 0 on the triangle's side. It is evaluated from the edge's canonical
// end (lower local vertex id), so the two triangles sharing an edge get exactly
// opposite values and a point can never be outside both (no ping-pong), and it
// is exactly 0 at both ends of the edge.
inline double orient(const SizeQuery::Tri& T, int k, double px, double py) {
  const Vec2& P = T.uv[(k + 1) % 3];
  const Vec2& Q = T.uv[(k + 2) % 3];
  const double dx = Q.x() - P.x(), dy = Q.y() - P.y();
  const Vec2& B = ((T.base >> k) & 1) ? Q : P;
  return dx * (py - B.y()) - dy * (px - B.x());
}

}  // namespace size_query_detail

struct SizeQuery::Face {
  int id = 0;
  std::vector<Tri> tris;       // #t, local ids as in the FacePatch
  Vec2 lo{0, 0}, hi{0, 0};     // uv range of the patch
  double period_u = 0, period_v = 0;
  int step_limit = 64;         // walk steps before the brute-force fallback
  // Grid of start triangles over the uv box (a start when the hint is far or missing).
  Vec2 grid_lo{0, 0};
  double inv_du = 0, inv_dv = 0;
  int nx = 1, ny = 1;
  std::vector<int> cell_tri;   // #nx*ny, a triangle containing (or near) each cell centre
  // Boundary chain (clamping points outside the domain, going around obstacles).
  std::vector<int> bslot;      // #3t, boundary edge of slot 3 t + k, or -1
  std::vector<size_query_detail::BEdge> bedges;
};

struct alignas(64) SizeQuery::StatSlot {
  std::atomic<uint64_t> queries{0}, visited{0}, max_visited{0}, fallbacks{0}, outside{0};
};

namespace size_query_detail {
// A face's walk data from its background patch and the vertex sizes h.
SizeQuery::Face build_face(const FacePatch& patch, int id, const std::vector<double>& h, double period_u,
                           double period_v);
}  // namespace size_query_detail

}  // namespace sizemesh
