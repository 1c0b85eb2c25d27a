// Slots too thin for the mesh between two components closed: one side's nodes moved into the other.
#include "mesher/close_gaps.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "core/predicates.h"

namespace sizemesh::mesh_union_detail {
namespace {

// Two components that lie on each other across a slot too thin for the mesh
// (a fin whose flat root face floats a few thousandths above a ridged
// fuselage, a pod resting on a wing) meet at a grazing angle, if at all:
// every triangle along such a cut, or across such a slot, would be a sliver.
// The slot is closed: the nodes of one side whose mean normal line meets the
// other side, facing it (normals opposed within 12 degrees: the surfaces
// meet, or would, in a wedge as thin as a sliver), less than half
// the local size outside it or less than a quarter inside, go a quarter of
// the local size into it along that line, where whole triangles of them do
// (a node alone, or a line of them, is a dent, not a slot). Their triangles
// are then inside the other component and dropped by the union, and the cut
// runs where the side's walls enter the other, at a steep angle.
//
// The side moved is the one with more nodes on the slot, the one that
// resolves it (a fin's root face, finer than the fuselage under it); the cut
// then lies on the other side's surface. A move that would make its side
// cross itself is undone.
struct GapSide {
  std::vector<std::pair<VI, Point>> moves;
};

GapSide gap_moves(const Tracked& side, const Mesh& other, const std::vector<double>& node_h) {
  using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
  GapSide out;
  const Mesh& m = side.m;
  double reach = 0;
  for (VI v : m.vertices())
    if (side.node[v] >= 0) reach = std::max(reach, 0.5 * node_h[side.node[v]]);
  if (!(reach > 0)) return out;
  auto grow = [reach](const CGAL::Bbox_3& b) {
    return CGAL::Bbox_3(b.xmin() - reach, b.ymin() - reach, b.zmin() - reach, b.xmax() + reach, b.ymax() + reach,
                        b.zmax() + reach);
  };
  const CGAL::Bbox_3 box = grow(PMP::bbox(m)), other_box = grow(PMP::bbox(other));
  std::vector<FI> near;
  for (FI f : other.faces())
    if (CGAL::do_overlap(PMP::face_bbox(f, other), box)) near.push_back(f);
  if (near.empty()) return out;
  const Tree tree(near.begin(), near.end(), other);
  std::map<VI, Point> to;
  for (VI v : m.vertices()) {
    const int n = side.node[v];
    if (n < 0 || !(node_h[n] > 0) || !CGAL::do_overlap(m.point(v).bbox(), other_box)) continue;
    K::Vector_3 normal(0, 0, 0);
    for (FI g : CGAL::faces_around_target(m.halfedge(v), m))
      if (g != Mesh::null_face()) normal = normal + PMP::compute_face_normal(g, m);
    if (normal.squared_length() == 0) continue;
    normal = normal / std::sqrt(normal.squared_length());
    const Point& x = m.point(v);
    const double gap = 0.5 * node_h[n], depth = 0.25 * node_h[n];
    // The nearest crossing of the normal line within [-depth, gap] whose
    // triangle faces this side.
    double best = HUGE_VAL;
    Point hit = x;
    for (int dir : {1, -1}) {
      const K::Ray_3 ray(x, dir * normal);
      std::vector<Tree::Intersection_and_primitive_id<K::Ray_3>::Type> hits;
      tree.all_intersections(ray, std::back_inserter(hits));
      for (const auto& [obj, f] : hits) {
        const Point* q = boost::get<Point>(&obj);
        if (!q) continue;
        const double t = std::sqrt(CGAL::to_double(CGAL::squared_distance(x, *q)));
        if (t > (dir > 0 ? gap : depth) || t >= std::abs(best)) continue;
        if (!(CGAL::to_double(PMP::compute_face_normal(f, other) * normal) < -kSliverCos)) continue;
        best = dir * t, hit = *q;
      }
    }
    if (best != HUGE_VAL) to[v] = hit + depth * normal;
  }
  // Only where whole triangles face across the slot.
  for (const auto& [v, x] : to) {
    bool whole = false;
    for (FI g : CGAL::faces_around_target(m.halfedge(v), m)) {
      if (g == Mesh::null_face()) continue;
      bool all = true;
      for (VI w : CGAL::vertices_around_face(m.halfedge(g), m)) all = all && to.count(w);
      whole = whole || all;
    }
    if (whole) out.moves.push_back({v, x});
  }
  return out;
}

// Moves `g` on `side`; false (and nothing moved) when it would cross itself.
bool apply_gap_moves(Tracked& side, const GapSide& g) {
  Mesh& m = side.m;
  std::vector<Point> was;
  CGAL::Bbox_3 moved;
  for (const auto& [v, x] : g.moves) {
    was.push_back(m.point(v));
    moved += x.bbox() + m.point(v).bbox();
    m.point(v) = x;
  }
  if (!crosses_within(m, moved)) return true;
  for (size_t i = 0; i < g.moves.size(); ++i) m.point(g.moves[i].first) = was[i];
  return false;
}

}  // namespace

void close_gaps(Tracked& part, Tracked& base, const std::vector<double>& node_h, std::set<int>& moved) {
  GapSide on_part = gap_moves(part, base.m, node_h), on_base = gap_moves(base, part.m, node_h);
  if (on_part.moves.empty() && on_base.moves.empty()) return;
  // The side with more nodes on the slot resolves it, and moves; a tie moves the part.
  const bool base_moves = on_base.moves.size() > on_part.moves.size();
  Tracked& side = base_moves ? base : part;
  const GapSide& g = base_moves ? on_base : on_part;
  if (!apply_gap_moves(side, g)) return;
  for (const auto& mv : g.moves) moved.insert(side.node[mv.first]);
}

}  // namespace sizemesh::mesh_union_detail
