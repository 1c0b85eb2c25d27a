// The size query service: the base-element search and interpolation (paper 4.2).
//
// Inputs (constructor)
//   bg        background mesh (paper 3.1); only its face patches (uv triangulations
//             with adjacency) and its global triangles are read, and copied, so bg
//             may be destroyed afterwards
//   h         #V sizes, one per global background vertex (xyz units)
//   period_u  per face (index face - 1) the period in u, 0 (or missing) when the
//   period_v  face is not periodic; take them from Geometry::face_period_u / _v
// Outputs (queries)
//   locate(face, uv, hint)  the base triangle of uv in that face's patch and the
//                           size interpolated linearly (barycentric) inside it
//   at(face, uv, hint)      the same as a SizeField; counts into stats()
//   at_xyz(xyz)             the size at the nearest background triangle in 3D
//
// How a query is answered (paper 4.2: "the search occurs in the two-dimensional
// parametric space of the input face"; walk-through after Shan et al. 2008):
//   1. uv of a periodic face is wrapped by its period into the patch's uv range;
//   2. the walk starts from the hint (the previous answer's triangle) or from
//      the triangle of a per-face coarse uv grid of start triangles built here,
//      whichever lies nearer the point (no hint: the grid's);
//   3. it steps from triangle to neighbour across an edge the point lies beyond,
//      never back across the entry edge, choosing between two such edges the one
//      the point is farthest beyond and, after a few steps, by a deterministic
//      coin (remembering stochastic walk), until the point is inside;
//   4. a walk blocked by the patch boundary follows the boundary chain to a
//      nearest boundary point; when that point is provably the nearest of the
//      whole domain and the point lies beyond it (slightly outside: trimming
//      tolerance, chord sagitta, round-off) the point gets the size there,
//      clamped, never extrapolated;
//   5. a walk blocked by the boundary of a non-convex domain (notches, slots,
//      holes) without being clearly outside goes around the obstacle: a straight
//      walk along the segment to the point that follows the boundary chain when
//      blocked and leaves it nearer the point (the Bug2 rule of path planning);
//      coming back to where it was blocked proves the point outside, and it gets
//      the size at the nearest point of that boundary loop;
//   6. a walk that exceeds its step limit (cycles in folded uv patches) or meets
//      a broken boundary chain ends in a counted brute-force scan.
// A face with no background triangles, a face id out of range or a non-finite
// uv makes locate()/at() throw sizemesh::Error naming the face (no surface
// evaluator is available here to fall back on).
//
// Every query is const and thread-safe; at() keeps per-thread counters that
// stats() sums.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "background/background_mesh.h"
#include "core/geometry.h"
#include "core/size_field.h"

namespace sizemesh {
class TriangleBVH;
}

namespace sizemesh {

// Counters of the base-element search (the paper reports the mean search depth).
struct QueryStats {
  uint64_t queries = 0;      // calls
  uint64_t visited = 0;      // triangles visited (walk steps, boundary steps, scanned by fallbacks)
  uint64_t max_visited = 0;  // most triangles visited by one call
  uint64_t fallbacks = 0;    // calls that ended in the brute-force scan
  uint64_t outside = 0;      // points outside the triangulated domain, clamped to its boundary
  void add(const QueryStats& o);
  double mean_visited() const { return queries ? static_cast<double>(visited) / queries : 0.0; }
};

class SizeQuery final : public SizeField {
 public:
  SizeQuery(const BackgroundMesh& bg, std::vector<double> h, std::vector<double> period_u = {},
            std::vector<double> period_v = {});
  ~SizeQuery() override;
  SizeQuery(SizeQuery&&) noexcept;
  SizeQuery& operator=(SizeQuery&&) noexcept;

  struct Hit {
    double h;  // interpolated size
    int tri;   // local triangle id in the face's patch: the next nearby call's hint
  };

  // Base-element search by walk-through (paper 4.2). hint < 0 or out of range: no hint.
  Hit locate(int face, const Vec2& uv, int hint, QueryStats* stats = nullptr) const;
  // Reference answer: scans every triangle of the face (containing, else nearest).
  Hit locate_brute_force(int face, const Vec2& uv) const;

  double at(int face, const Vec2& uv, int& hint) const override;
  // Nearest background triangle in xyz (bounding-volume hierarchy), barycentric there.
  double at_xyz(const Vec3& xyz) const override;

  QueryStats stats() const;
  void reset_stats();

  // Start from the nearer of the hint and the start grid's triangle (default),
  // or from the hint alone as in the paper. Set before querying (not thread-safe).
  void set_grid_with_hint(bool on) { grid_with_hint_ = on; }
  // Surface point of (face, uv). When set, a face with no background triangles
  // answers with at_xyz() of that point instead of throwing.
  void set_surface(std::function<Vec3(int face, const Vec2& uv)> surface) { surface_ = std::move(surface); }

  int num_faces() const;
  int num_triangles(int face) const;

  // Per-triangle data of the walk, precomputed (one 96-byte record per triangle).
  struct Tri {
    std::array<Vec2, 3> uv;      // corner uv (counter-clockwise)
    std::array<double, 3> h;     // corner sizes
    std::array<int, 3> adj;      // neighbour across the edge opposite corner k, -1 on the boundary
    std::array<int8_t, 3> back;  // that edge's index in the neighbour
    uint8_t base = 0;            // bit k: edge k is evaluated from corner k+2 (else k+1)
  };
  struct Face;  // a face's triangles, start grid and periods
  struct StatSlot;

 private:
  const Face& face_data(int face) const;
  Hit walk(const Face& f, const Vec2& p, int start, QueryStats& st) const;
  Hit clamp_to_boundary(const Face& f, const Vec2& p, int t, int k, QueryStats& st) const;
  Hit go_around(const Face& f, const Vec2& p, int t, QueryStats& st) const;
  Hit brute_force(const Face& f, const Vec2& p, QueryStats& st) const;
  void count(const QueryStats& one) const;

  std::vector<Face> faces_;      // index face - 1
  std::unique_ptr<TriangleBVH> bvh_;       // background triangles in xyz, for at_xyz
  std::vector<std::array<double, 3>> tri_h_;  // #T corner sizes
  std::unique_ptr<StatSlot[]> slots_;
  bool grid_with_hint_ = true;
  std::function<Vec3(int, const Vec2&)> surface_;
};

// The size query over a model's faces: periods from g, and g's surface for
// faces with no background triangles. g must outlive the query.
SizeQuery size_query_for(const Geometry& g, const BackgroundMesh& bg, std::vector<double> h);

}  // namespace sizemesh
