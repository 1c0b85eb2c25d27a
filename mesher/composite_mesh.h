// The mesh a composite face is re-meshed on (mesher/composite_remesh.h): its
// triangles with each node's star, the edges it must keep, each node's place
// on the B-rep, and the local operations (collapse, split, flip, smooth)
// that cross virtual curves. Every node stays on the exact B-rep: a node
// moved or made is projected onto the face of the input mesh's triangle
// nearest to it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "core/geometry.h"
#include "core/mesh_topology.h"
#include "core/size_field.h"
#include "core/triangle_bvh.h"
#include "mesher/surface_mesh.h"

namespace sizemesh::composite_detail {

constexpr double kCos30 = 0.8660254037844386;
constexpr double kCos45 = 0.7071067811865476;
// A collapse never leaves an edge longer than this many sizes; a split cuts
// an edge above it (the front's own bound, SizeField::length_excess, is 1.4).
constexpr double kLongEdge = 1.5;
// Operations may make triangles down to this smallest angle where those
// they replace were no worse.
constexpr double kFairDeg = 25.0;
// Stars and edge pairs whose smallest angle is at least this are left as they are.
constexpr double kSmoothBelow = 35.0;

struct OpCount {
  int collapsed = 0, split = 0, flipped = 0, smoothed = 0, slid = 0;
};

class CompositeMesh {
 public:
  // hard: the edges (edge_key) the mesh keeps; corner: nodes that never move.
  CompositeMesh(SurfaceMesh& s, const Geometry& g, const SizeField& h, std::unordered_set<uint64_t> hard,
                std::vector<char> corner);

  int num_nodes() const { return static_cast<int>(xyz_.size()); }
  bool dead(int t) const { return dead_[t] != 0; }
  // Free: on no kept edge, so it moves anywhere on its composite face.
  bool free(int n) const { return hard_degree_[n] == 0 && !corner_[n]; }
  // Never moves nor merges away (nodes made by the re-mesh are no corners).
  bool corner(int n) const { return corner_[n] != 0; }
  double size(int n) {
    if (size_[n] < 0) {
      int hint = -1;
      size_[n] = place_[n].face ? h_.at(place_[n].face, place_[n].uv, hint) : 0.0;
    }
    return size_[n];
  }
  const Vec3& xyz(int n) const { return xyz_[n]; }
  const std::vector<int>& star(int n) const { return node_tris_[n]; }
  double star_min_angle(const std::vector<int>& tris) const;
  // The shortest and longest edge at node n.
  std::array<double, 2> edge_range(int n) const {
    std::array<double, 2> r{HUGE_VAL, 0.0};
    for (int t : node_tris_[n])
      for (int m : tris_[t])
        if (m != n) {
          const double len = (xyz_[m] - xyz_[n]).norm();
          r[0] = std::min(r[0], len), r[1] = std::max(r[1], len);
        }
    return r;
  }
  std::vector<int> neighbours(int n) const;  // in rank order
  // Node a before node b: by position (made nodes after, in the order made).
  int rank(int n) const { return rank_[n]; }

  bool collapse(int b, int a, OpCount& c);  // b merged into a (a stays)
  bool split(int a, int b, OpCount& c);     // a soft edge cut at its middle
  bool flip(int a, int b, OpCount& c);      // a soft edge turned when the smallest angle grows
  bool smooth(int n, OpCount& c);           // a free node to its neighbours' centroid, on the surface
  // A node of a kept chain on a B-rep curve moved along the curve, up to
  // half way to a chain neighbour, where its star's smallest angle grows most:
  // across a strip between two curves, nodes facing each other stagger.
  bool slide(int n, OpCount& c);

  // Writes the mesh back: dead triangles and unused nodes gone, each changed
  // triangle given the face under its centroid and uvs there. Returns each
  // input node's new id (-1: gone).
  // fresh (optional): per output triangle, 1 when the re-mesh made or moved it.
  std::vector<int> write_back(std::vector<char>* fresh = nullptr);

 private:
  struct Place {
    int face = 0;
    Vec2 uv{0, 0};
  };
  bool project(const Vec3& p, double reach, Vec3& x, Place& at) const;
  double edge_size(int a, int b) { return 0.5 * (size(a) + size(b)); }
  bool is_hard(int a, int b) const { return hard_.count(edge_key(a, b)) != 0; }
  int add_node(const Vec3& x, const Place& at);
  int add_tri(const std::array<int, 3>& t, int face);
  void kill(int t);

  Vec3 normal(const std::array<int, 3>& t) const;
  // The unit surface normal (out of the shell) at a place; zero where there is none.
  Vec3 surface_normal(const Place& at) const;
  // The parameter of curve c nearest to x (samples, then Newton); NaN on failure.
  double curve_parameter(int c, const Vec3& x) const;
  // Node n's surface normal (cached); zero on a kept edge, where its faces' differ.
  Vec3 node_normal(int n);
  // The chord's height off the surface between two points with these
  // normals, about L theta / 8 (theta the normals' angle); 0 where one is unknown.
  static double sag(const Vec3& xa, const Vec3& na, const Vec3& xb, const Vec3& nb);
  // A new chord is accurate when it turns by no more than the face's bound
  // (phi_c) and its height stays within the deviation bound, or when it is
  // no worse than the chords it replaces (`old`, their largest height).
  bool accurate(const Vec3& xa, const Vec3& na, const Vec3& xb, const Vec3& nb, int face, double old) const;
  // True when every triangle of `tris` faces along the surface normal at `at`.
  bool facing(const std::vector<std::array<Vec3, 3>>& tris, const Place& at) const;
  std::array<int, 2> edge_tris(int a, int b) const;

  SurfaceMesh& s_;
  const Geometry& g_;
  const SizeField& h_;
  std::unordered_set<uint64_t> hard_;
  std::vector<char> corner_;
  std::vector<Vec3> xyz_;
  std::vector<std::array<int, 3>> tris_;
  std::vector<int> tri_face_;
  std::vector<char> dead_, changed_;
  std::vector<std::vector<int>> node_tris_;
  std::vector<int> hard_degree_;
  std::vector<double> size_;
  std::vector<Place> place_;
  std::vector<Vec3> normal_;
  std::vector<int> curve_;     // the B-rep curve an input node lies on; 0 none
  std::vector<int> rank_;
  std::function<bool(int, int)> before_ = [this](int a, int b) { return rank_[a] < rank_[b]; };
  std::vector<char> slid_;     // moved along its curve
  std::unordered_map<uint64_t, Vec2> input_uv_;  // (node, face) -> the input triangles' uv
  std::vector<char> has_normal_;
  std::unique_ptr<TriangleBVH> reference_;          // the input mesh
  std::vector<int> ref_face_;
  std::vector<std::array<Vec2, 3>> ref_uv_;
};

}  // namespace sizemesh::composite_detail
