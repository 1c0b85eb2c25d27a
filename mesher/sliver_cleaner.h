// The junction sliver remover's state (Cleaner: the mesh, each node's triangles) and its local operations.
#pragma once

#include <algorithm>
#include <array>
#include <functional>
#include <vector>

#include "core/geometry.h"
#include "core/predicates.h"
#include "core/size_field.h"
#include "mesher/junction_slivers.h"
#include "mesher/surface_mesh.h"

namespace sizemesh::junction_slivers_detail {

// The smallest angle of a set of triangles, and how many are under 12 degrees.
struct Shape {
  int thin = 0;
  double min = 180;
  void add(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double m = min_angle_deg(a, b, c);
    thin += m < kSliverDeg;
    min = std::min(min, m);
  }
  // Better than `old`: fewer thin triangles, none far thinner than the
  // thinnest before (the strip's next ones go in later steps), or as many
  // and a larger smallest angle.
  bool better_than(const Shape& old) const {
    return (thin < old.thin && min > 0.25 * old.min) || (thin <= old.thin && min > old.min + 1e-9);
  }
};

// The mesh being cleaned: each node's triangles, those removed, the nodes merged.
class Cleaner {
 public:
  Cleaner(SurfaceMesh& s, const Geometry& g, const SizeField& h)
      : s_(s), g_(g), h_(h), node_tris_(s.xyz.size()), dead_(s.tris.size(), 0), merged_into_(s.xyz.size(), -1) {
    for (size_t t = 0; t < s.tris.size(); ++t)
      for (int n : s.tris[t]) node_tris_[n].push_back(static_cast<int>(t));
  }

  double min_angle(int t) const {
    const auto& tr = s_.tris[t];
    return min_angle_deg(s_.xyz[tr[0]], s_.xyz[tr[1]], s_.xyz[tr[2]]);
  }
  bool dead(int t) const { return dead_[t] != 0; }
  const std::vector<int>& merged_into() const { return merged_into_; }
  const std::vector<char>& dead_tris() const { return dead_; }

  std::vector<int> alive(int n) const {
    std::vector<int> out;
    for (int t : node_tris_[n])
      if (!dead_[t]) out.push_back(t);
    return out;
  }

  // The best operation that removes thin triangle t, applied; the triangles
  // it made are appended to `made`. False when none improves on t's
  // neighbourhood.
  bool improve(int t, std::vector<int>& made, JunctionSliverResult& count);

 private:
  int corner(int t, int n) const {
    return static_cast<int>(std::find(s_.tris[t].begin(), s_.tris[t].end(), n) - s_.tris[t].begin());
  }
  std::vector<int> faces(int n) const;
  std::vector<int> neighbours(int n) const;
  // The cosine of the angle between a triangle's normal and its face's
  // surface normal at its centroid; 1 where the surface has none (a pole).
  double lean(int f, const std::array<Vec3, 3>& x, const std::array<Vec2, 3>& uv) const;
  double lean(int t) const;
  // Node n's uv in face f near `near`: from a triangle of f at n, else by
  // projecting n onto f.
  bool uv_in(int n, int f, const Vec2& near, Vec2& out) const;
  // True when a triangle of face f on nodes n, under 12 degrees, is an ear
  // of its face's boundary (two of its edges on it, `face_across` giving
  // another face or none) at a corner that is not its smallest angle: no
  // sharp corner of the face forces it.
  bool thin_ear(int f, const std::array<int, 3>& n, const std::function<int(int, int)>& face_across) const;

  // The size wanted at node n (the finest of its faces').
  double size_at(int n) const;

  // Node b merged into its neighbour a (a stays where it is): allowed when a
  // is on every face b is on (and on b's curve), or when they are closer than
  // `reach` or tan(12 deg) of the size wanted there; never a B-rep point moved, never
  // an edge used more than twice after it.
  bool collapse(int b, int a, double reach, bool apply, Shape& before, Shape& after);

  // Triangle t = (r, p, q) with its largest angle at r (corner kr), and the
  // one triangle t2 = (q, p, o) across (p, q), o not yet joined to r: what a
  // flip or a pinch of t changes. False when (p, q) is not an inner edge of
  // the mesh or r and o are joined already.
  struct Across {
    int r, p, q, kr, t2, o;
    double angle;  // at r, degrees
  };
  bool across_largest(int t, Across& x) const;
  // Triangle x no longer at node n.
  void drop_tri(int n, int x) {
    auto& v = node_tris_[n];
    v.erase(std::remove(v.begin(), v.end(), x), v.end());
  }

  // The edge opposite t's largest angle flipped, when the triangle across it
  // is of the same face.
  bool flip(int t, bool apply, Shape& before, Shape& after);

  // Thin triangle t = (r, p, q) with its largest angle (over 90 degrees)
  // at r, a node of a curve or junction, where the triangle across (p, q) is
  // of another face: r lies within a sliver's height of that face boundary
  // (a junction touching a curve), and is put on it. t goes, the triangle
  // across is split at r in two.
  bool pinch(int t, bool apply, Shape& before, Shape& after);

  SurfaceMesh& s_;
  const Geometry& g_;
  const SizeField& h_;
  std::vector<std::vector<int>> node_tris_;
  std::vector<char> dead_;
  std::vector<int> merged_into_;
  int flipped_other_ = -1;
};

}  // namespace sizemesh::junction_slivers_detail
