#include "mesher/mesh_union.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <Eigen/Dense>
#include <boost/iterator/function_output_iterator.hpp>
#include <algorithm>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <tuple>
#include <unordered_map>

#include "geometry/predicates.h"
#include "geometry/triangle_bvh.h"
#include "mesher/self_intersection.h"
#include "mesher/snap.h"
#include "mesher/target_sizes.h"

namespace sizemesh {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using VI = Mesh::Vertex_index;
using FI = Mesh::Face_index;
using EI = Mesh::Edge_index;

Vec3 vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }
Point point(const Vec3& v) { return Point(v.x(), v.y(), v.z()); }

// A CGAL mesh that remembers, per triangle, the source triangle and CAD face
// and, per vertex, the source node (-1 for a node the cut or the remesh made).
struct Tracked {
  Mesh m;
  Mesh::Property_map<FI, int> tri, face;
  Mesh::Property_map<VI, int> node;
  Mesh::Property_map<EI, bool> cut;  // on a junction curve
  Tracked() { attach(); }
  Tracked(const Tracked& o) : m(o.m) { attach(); }
  Tracked& operator=(const Tracked&) = delete;
  void attach() {
    tri = m.add_property_map<FI, int>("f:tri", -1).first;
    face = m.add_property_map<FI, int>("f:cad", 0).first;
    node = m.add_property_map<VI, int>("v:node", -1).first;
    cut = m.add_property_map<EI, bool>("e:cut", false).first;
  }
};

// The triangles `ids` of `s` as a tracked mesh; false when they are not a
// manifold surface.
bool build(const SurfaceMesh& s, const std::vector<int>& ids, Tracked& t) {
  std::unordered_map<int, VI> vertex;
  for (int id : ids)
    for (int n : s.tris[id])
      if (vertex.emplace(n, VI()).second) {
        const VI v = t.m.add_vertex(point(s.xyz[n]));
        vertex[n] = v;
        t.node[v] = n;
      }
  for (int id : ids) {
    const auto& tr = s.tris[id];
    const FI f = t.m.add_face(vertex[tr[0]], vertex[tr[1]], vertex[tr[2]]);
    if (f == Mesh::null_face()) return false;
    t.tri[f] = id;
    t.face[f] = s.tri_face[id];
  }
  return true;
}

constexpr const char* kCrossesItself = "its mesh intersects itself";

// The triangles of m that cross another triangle of m.
std::vector<FI> crossing_triangles(const Mesh& m) {
  std::set<FI> out;
  PMP::self_intersections(m, boost::make_function_output_iterator([&out](const std::pair<FI, FI>& p) {
                            out.insert(p.first);
                            out.insert(p.second);
                          }));
  return {out.begin(), out.end()};
}

// Why `t` cannot take part in a union of volumes; empty when it can (it is
// then oriented outward). Its triangles that cross each other go to `crossing`.
std::string unfit(Tracked& t, std::vector<FI>& crossing) {
  if (t.m.is_empty()) return "it has no triangles";
  if (!CGAL::is_closed(t.m)) return "its mesh is not closed";
  crossing = crossing_triangles(t.m);
  if (!crossing.empty()) {
    // A skin that folds through itself: it bounds a volume where it does not
    // cross, so the outward test looks at its extreme vertex only.
    if (!PMP::is_outward_oriented(t.m)) PMP::reverse_face_orientations(t.m);
    return kCrossesItself;
  }
  if (!PMP::does_bound_a_volume(t.m)) PMP::orient_to_bound_a_volume(t.m);
  if (!PMP::does_bound_a_volume(t.m)) return "its mesh does not bound a volume";
  return {};
}

// True when triangles of m within `box` intersect each other: where a piece
// joined, the rest of m being as it was.
bool crosses_within(const Mesh& m, const CGAL::Bbox_3& box) {
  std::vector<FI> near;
  for (FI f : m.faces())
    if (CGAL::do_overlap(PMP::face_bbox(f, m), box)) near.push_back(f);
  return PMP::does_self_intersect(near, m);
}

// True when every corner of the triangles `tris` of `m` lies strictly inside
// the closed mesh `base`: a fold there, or the whole piece, is dropped by the union.
bool inside_base(const Mesh& m, const std::vector<FI>& tris, const Mesh& base) {
  const CGAL::Side_of_triangle_mesh<Mesh, K> side(base);
  for (FI f : tris)
    for (VI v : CGAL::vertices_around_face(m.halfedge(f), m))
      if (side(m.point(v)) != CGAL::ON_BOUNDED_SIDE) return false;
  return true;
}

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

// Closes the slots between `part` and `base` (see GapSide); the source nodes
// moved go to `moved`.
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

// Triangles the corefinement made without telling its visitor (it splits a
// triangle whose corners all lie on the other mesh, where two surfaces touch
// in a plane, by plain Euler operations) take the source triangle and CAD
// face of a neighbour in the plane of the triangle they were split from, else
// of any neighbour that has one.
void adopt_orphans(Tracked& t) {
  const Mesh& m = t.m;
  auto normal = [&](FI f) {
    std::array<Point, 3> p;
    int k = 0;
    for (VI v : CGAL::vertices_around_face(m.halfedge(f), m)) p[k++] = m.point(v);
    return CGAL::unit_normal(p[0], p[1], p[2]);
  };
  std::vector<FI> orphans;
  for (FI f : m.faces())
    if (t.face[f] == 0) orphans.push_back(f);
  for (int pass = 0; pass < 2 && !orphans.empty(); ++pass) {
    for (bool changed = true; changed && !orphans.empty();) {
      changed = false;
      std::vector<FI> left;
      for (FI f : orphans) {
        const K::Vector_3 n = normal(f);
        FI best = Mesh::null_face();
        double best_dot = pass == 0 ? 1 - 1e-9 : -2;
        for (auto h : CGAL::halfedges_around_face(m.halfedge(f), m)) {
          const FI g = m.face(m.opposite(h));
          if (g == Mesh::null_face() || t.face[g] == 0) continue;
          const double d = CGAL::to_double(n * normal(g));
          if (d > best_dot) best_dot = d, best = g;
        }
        if (best == Mesh::null_face()) {
          left.push_back(f);
          continue;
        }
        t.face[f] = t.face[best];
        t.tri[f] = t.tri[best];
        changed = true;
      }
      orphans.swap(left);
    }
  }
}

// t renumbered in an order that depends on the geometry alone: vertices by
// their coordinates, triangles by their vertices. CGAL's corefinement breaks
// ties between boxes by their heap address, so its new vertices and faces
// come in an order that changes from run to run, and the band remesh, which
// visits them in order, would give a different mesh each time.
void renumber(Tracked& t) {
  const Mesh& m = t.m;
  std::vector<VI> vertices;
  for (FI f : m.faces())
    for (VI v : CGAL::vertices_around_face(m.halfedge(f), m)) vertices.push_back(v);
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  auto key = [&](VI v) {
    const Point& p = m.point(v);
    return std::make_tuple(p.x(), p.y(), p.z(), t.node[v]);
  };
  std::stable_sort(vertices.begin(), vertices.end(), [&](VI a, VI b) { return key(a) < key(b); });
  Tracked out;
  std::vector<VI> to(m.number_of_vertices() + m.number_of_removed_vertices(), Mesh::null_vertex());
  for (VI v : vertices) {
    const VI w = out.m.add_vertex(m.point(v));
    out.node[w] = t.node[v];
    to[v.idx()] = w;
  }
  // Each triangle from its lowest new vertex, turning as before.
  std::vector<std::pair<std::array<uint32_t, 3>, FI>> faces;
  for (FI f : m.faces()) {
    std::array<uint32_t, 3> c;
    int k = 0;
    for (VI v : CGAL::vertices_around_face(m.halfedge(f), m)) c[k++] = static_cast<uint32_t>(to[v.idx()]);
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    faces.emplace_back(c, f);
  }
  std::sort(faces.begin(), faces.end());
  for (const auto& [c, f] : faces) {
    const FI g = out.m.add_face(VI(c[0]), VI(c[1]), VI(c[2]));
    if (g == Mesh::null_face()) return;  // not a manifold surface: left as it was
    out.tri[g] = t.tri[f];
    out.face[g] = t.face[f];
  }
  for (EI e : m.edges()) {
    if (!t.cut[e]) continue;
    const VI a = to[m.vertex(e, 0).idx()], b = to[m.vertex(e, 1).idx()];
    if (a == Mesh::null_vertex() || b == Mesh::null_vertex()) continue;  // on no face
    const auto h = out.m.halfedge(a, b);
    if (h != Mesh::null_halfedge()) out.cut[out.m.edge(h)] = true;
  }
  t.m = out.m;
  t.attach();
}

// Carries the source triangle, CAD face and node through the corefinement.
struct FollowState {
  Tracked* a = nullptr;
  Tracked* b = nullptr;
  int tri = -1, face = 0;
  Tracked& of(const Mesh& m) { return &m == &a->m ? *a : *b; }
};
struct Follow : PMP::Corefinement::Default_visitor<Mesh> {
  std::shared_ptr<FollowState> s = std::make_shared<FollowState>();
  void before_subface_creations(FI f, Mesh& m) {
    Tracked& t = s->of(m);
    s->tri = t.tri[f];
    s->face = t.face[f];
  }
  void after_subface_created(FI f, Mesh& m) {
    Tracked& t = s->of(m);
    t.tri[f] = s->tri;
    t.face[f] = s->face;
  }
  void after_face_copy(FI from, const Mesh& ms, FI to, Mesh& mt) {
    Tracked &a = s->of(ms), &b = s->of(mt);
    b.tri[to] = a.tri[from];
    b.face[to] = a.face[from];
  }
  void after_vertex_copy(VI from, const Mesh& ms, VI to, Mesh& mt) { s->of(mt).node[to] = s->of(ms).node[from]; }
};

// The triangles `ids` in pieces connected across edges: the closed ones
// (every edge used twice), largest first, and the triangles of open ones.
std::vector<std::vector<int>> closed_pieces(const SurfaceMesh& s, const std::vector<int>& ids, std::vector<int>& open) {
  std::vector<int> parent(ids.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<std::pair<int, int>, std::vector<int>> edges;
  for (size_t i = 0; i < ids.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const int a = s.tris[ids[i]][k], b = s.tris[ids[i]][(k + 1) % 3];
      edges[std::minmax(a, b)].push_back(static_cast<int>(i));
    }
  std::vector<bool> open_root(ids.size(), false);
  for (const auto& [e, uses] : edges)
    for (size_t j = 1; j < uses.size(); ++j) parent[find(uses[j])] = find(uses[0]);
  for (const auto& [e, uses] : edges)
    if (uses.size() != 2) open_root[find(uses[0])] = true;
  std::map<int, std::vector<int>> by_root;
  for (size_t i = 0; i < ids.size(); ++i) {
    const int root = find(static_cast<int>(i));
    if (open_root[root]) open.push_back(ids[i]);
    else by_root[root].push_back(ids[i]);
  }
  std::vector<std::vector<int>> out;
  for (auto& [root, tris] : by_root) out.push_back(std::move(tris));
  std::stable_sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.size() > y.size(); });
  return out;
}

// uv of node n on face f, from the first triangle of f that uses it.
struct NodeUV {
  std::unordered_map<uint64_t, Vec2> at;
  static uint64_t key(int n, int f) { return (uint64_t(uint32_t(n)) << 32) | uint32_t(f); }
  explicit NodeUV(const SurfaceMesh& s) {
    for (size_t t = 0; t < s.tris.size(); ++t)
      for (int k = 0; k < 3; ++k) at.emplace(key(s.tris[t][k], s.tri_face[t]), s.tri_uv[t][k]);
  }
  const Vec2* find(int n, int f) const {
    const auto it = at.find(key(n, f));
    return it == at.end() ? nullptr : &it->second;
  }
};

// The source triangle of face f nearest a point, over all of the face's
// triangles (a tree per face, built when first asked): the start of a
// projection for a node the cut or the band remesh made far from any source
// triangle it knows.
class FaceTriangles {
 public:
  explicit FaceTriangles(const SurfaceMesh& s) : s_(s) {
    for (size_t t = 0; t < s.tris.size(); ++t) of_face_[s.tri_face[t]].push_back(static_cast<int>(t));
  }
  // The nearest triangle of f to x (-1 when f has none).
  int nearest(int f, const Vec3& x) {
    auto it = tree_.find(f);
    if (it == tree_.end()) {
      const auto list = of_face_.find(f);
      if (list == of_face_.end()) return -1;
      std::vector<std::array<int, 3>> tris;
      for (int t : list->second) tris.push_back(s_.tris[t]);
      it = tree_.emplace(f, std::make_unique<TriangleBVH>(s_.xyz, tris)).first;
    }
    const TriangleBVH::Closest c = it->second->closest(x);
    return c.tri < 0 ? -1 : of_face_[f][c.tri];
  }

 private:
  const SurfaceMesh& s_;
  std::unordered_map<int, std::vector<int>> of_face_;
  std::unordered_map<int, std::unique_ptr<TriangleBVH>> tree_;
};

// Pairs of triangles of m that intersect, both within `zone` (boxes): a
// remesh inside the zone changes no pair outside it.
size_t crossing_pairs(const Mesh& m, const std::vector<CGAL::Bbox_3>& zone) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, size_t>;
  std::vector<Box> zones, faces;
  CGAL::Bbox_3 all;
  for (size_t i = 0; i < zone.size(); ++i) zones.emplace_back(zone[i], i), all += zone[i];
  std::vector<FI> handles;
  for (FI f : m.faces())
    if (const CGAL::Bbox_3 b = PMP::face_bbox(f, m); CGAL::do_overlap(b, all))
      faces.emplace_back(b, handles.size()), handles.push_back(f);
  std::vector<char> near(handles.size(), 0);
  CGAL::box_intersection_d(zones.begin(), zones.end(), faces.begin(), faces.end(),
                           [&](const Box&, const Box& f) { near[f.info()] = 1; });
  std::vector<FI> within;
  for (size_t i = 0; i < handles.size(); ++i)
    if (near[i]) within.push_back(handles[i]);
  size_t n = 0;
  PMP::self_intersections(within, m, boost::make_function_output_iterator([&n](const std::pair<FI, FI>&) { ++n; }));
  return n;
}

// The bands along the cuts (the triangles touching a cut node and one ring
// more) remeshed to the size map's size there: CGAL's isotropic remeshing,
// the cut curves and CAD face borders kept as constraints (their nodes slide
// along them), B-rep points and nodes where three faces meet fixed. A
// periodic face counts as two halves of its period, so its seam stays a line
// of edges (the cut faces' remesher walks the face's region in uv across it).
// One call per size class (a factor 1.25 apart), each over every band of
// that class.
void remesh_bands(Tracked& t, const SurfaceMesh& s, const Geometry& g, const std::vector<double>& node_h,
                  std::map<int, std::set<int>>& near_cut, MeshUnionResult& out) {
  Mesh& m = t.m;
  auto patch = m.add_property_map<FI, int>("f:patch", 0).first;
  for (FI f : m.faces()) {
    const int face = t.face[f], src = t.tri[f];
    int half = 0;
    if (src >= 0) {
      const Vec2 c = (s.tri_uv[src][0] + s.tri_uv[src][1] + s.tri_uv[src][2]) / 3.0;
      const UVBox box = g.face_uv_bounds(face);
      for (int axis = 0; axis < 2; ++axis) {
        const double period = axis == 0 ? g.face_wrap_u(face) : g.face_wrap_v(face);
        if (!(period > 0)) continue;
        const double w = c[axis] - box.lo[axis];
        half |= (w - std::floor(w / period) * period >= 0.5 * period) << axis;
      }
    }
    patch[f] = 4 * face + half;
  }
  std::set<VI> ring;
  for (EI e : m.edges())
    if (t.cut[e]) ring.insert(m.vertex(e, 0)), ring.insert(m.vertex(e, 1));
  if (ring.empty()) return;
  std::set<FI> band;
  for (int step = 0; step < 2; ++step) {
    std::set<VI> next = ring;
    for (VI v : ring)
      for (FI f : CGAL::faces_around_target(m.halfedge(v), m))
        if (f != Mesh::null_face() && band.insert(f).second)
          for (VI w : CGAL::vertices_around_face(m.halfedge(f), m)) next.insert(w);
    ring.swap(next);
  }
  // Connected bands, each with the median target size of its source nodes.
  std::map<FI, int> region;
  std::vector<double> length;
  for (FI seed : band) {
    if (region.count(seed)) continue;
    const int id = static_cast<int>(length.size());
    std::vector<FI> stack{seed};
    region[seed] = id;
    std::vector<double> sizes;
    while (!stack.empty()) {
      const FI f = stack.back();
      stack.pop_back();
      for (VI v : CGAL::vertices_around_face(m.halfedge(f), m)) {
        if (t.node[v] >= 0 && node_h[t.node[v]] > 0) sizes.push_back(node_h[t.node[v]]);
        for (FI g : CGAL::faces_around_target(m.halfedge(v), m))
          if (g != Mesh::null_face() && band.count(g) && region.emplace(g, id).second) stack.push_back(g);
      }
    }
    std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
    length.push_back(sizes.empty() ? 0.0 : sizes[sizes.size() / 2]);
  }
  auto fixed = m.add_property_map<VI, bool>("v:fixed", false).first;
  for (FI b : band) {
    if (t.tri[b] >= 0) near_cut[t.face[b]].insert(t.tri[b]);
    for (VI v : CGAL::vertices_around_face(m.halfedge(b), m)) {
      const int n = t.node[v];
      std::set<int> faces;
      for (FI f : CGAL::faces_around_target(m.halfedge(v), m))
        if (f != Mesh::null_face()) faces.insert(t.face[f]);
      fixed[v] = (n >= 0 && s.node_dim[n] == 0) || faces.size() >= 3;
    }
  }
  std::map<int, std::vector<FI>> classes;  // size class -> band faces
  for (const auto& [f, id] : region)
    if (length[id] > 0) classes[static_cast<int>(std::floor(std::log(length[id]) / std::log(1.25)))].push_back(f);
  for (auto& [c, faces] : classes) {
    // CGAL's remesher does not promise a surface free of self-intersections
    // (a band folds where two surfaces graze): a class that adds one is undone.
    // Its triangles stay within an edge length of the band's, so the pairs
    // counted are those near the band, before and after (the corefinement
    // leaves a few of its own, from rounding its points to doubles).
    const double length = std::pow(1.25, c + 0.5);
    std::vector<CGAL::Bbox_3> zone;
    for (FI f : faces) {
      const CGAL::Bbox_3 b = PMP::face_bbox(f, m);
      zone.emplace_back(b.xmin() - length, b.ymin() - length, b.zmin() - length, b.xmax() + length,
                        b.ymax() + length, b.zmax() + length);
    }
    const size_t crossing = crossing_pairs(m, zone);
    const Mesh before = m;
    // Their CAD faces, and those across their edges: a split edge on the
    // band's rim splits the triangle beyond it too.
    std::set<int> touched;
    for (FI f : faces) {
      touched.insert(t.face[f]);
      for (auto h : CGAL::halfedges_around_face(m.halfedge(f), m))
        if (const FI across = m.face(m.opposite(h)); across != Mesh::null_face()) touched.insert(t.face[across]);
    }
    // Splits, collapses and flips only, no tangential relaxation: the band's
    // nodes go onto their CAD surfaces afterwards, and a node slid along the
    // facets where the surface curves folds its triangles once put there
    // (inverted triangles on four aircraft: 34 with relaxation, 8 without);
    // CGAL's relaxation also computes the whole mesh's vertex normals at
    // each class and iteration.
    PMP::isotropic_remeshing(faces, length, m,
                             PMP::parameters::number_of_iterations(3)
                                 .edge_is_constrained_map(t.cut)
                                 .vertex_is_constrained_map(fixed)
                                 .face_patch_map(patch)
                                 .relax_constraints(true)
                                 .number_of_relaxation_steps(0));
    for (FI f : m.faces()) t.face[f] = patch[f] / 4;
    if (crossing_pairs(m, zone) > crossing) {
      m = before;
      t.attach();
      fixed = m.property_map<VI, bool>("v:fixed").first;
      patch = m.property_map<FI, int>("f:patch").first;
      ++out.band_classes_undone;
    } else {
      out.band_triangles += static_cast<int>(faces.size());
      out.band_faces.insert(touched.begin(), touched.end());
    }
  }
  m.remove_property_map(fixed);
  m.remove_property_map(patch);
}

// Nodes put on their CAD surfaces where the surfaces graze may cross the
// other side's facets, which stay chords: the nodes of every intersecting
// pair that involves a moved node go back to their place on the meshes
// (which did not intersect there), a few rounds, then every moved node does.
// Returns the intersecting pairs left, or -1 when that last step left them
// uncounted.
long long keep_apart(SurfaceMesh& r, const std::vector<Vec3>& before_snap) {
  auto moved = [&](int t) {
    for (int n : r.tris[t])
      if (r.xyz[n] != before_snap[n]) return true;
    return false;
  };
  for (int round = 0; round < 4; ++round) {
    const SelfIntersections hits = find_self_intersections(r, static_cast<size_t>(-1));
    bool any = false;
    for (const auto& pair : hits.kept) {
      if (!moved(pair[0]) && !moved(pair[1])) continue;
      any = true;
      if (round == 3) break;
      for (int t : pair)
        for (int n : r.tris[t]) r.xyz[n] = before_snap[n];
    }
    if (!any) return hits.pairs;
    if (round == 3) r.xyz = before_snap;
  }
  return -1;
}

}  // namespace

void count_junction_node(MeshUnionResult& u, const Geometry& g, const Vec3& x, std::vector<std::pair<int, Vec2>> on,
                         double off) {
  double gap = 0;
  bool projected = true;
  for (auto& [face, uv] : on)
    if (g.project_to_face(face, x, uv)) gap = std::max(gap, (g.eval_face(face, uv).p - x).norm());
    else projected = false;
  if (projected) u.max_junction_gap = std::max(u.max_junction_gap, gap);
  u.junction_nodes_unprojected += !projected;
  u.junction_nodes_off += !projected || gap > off;
}

MeshUnionResult unite_meshes(SurfaceMesh& s, const Geometry& g, const SizeFunction& h,
                             const std::vector<std::vector<int>>& parts) {
  MeshUnionResult out;
  out.failures.assign(parts.size(), {});
  if (parts.empty()) return out;
  // Triangles per part; the rest is the base, its closed components united,
  // its open ones (sheets) kept as they are.
  std::unordered_map<int, int> part_of_face;
  for (size_t p = 0; p < parts.size(); ++p)
    for (int f : parts[p]) part_of_face[f] = static_cast<int>(p);
  std::vector<std::vector<int>> part_tris(parts.size());
  std::vector<int> rest;
  for (size_t t = 0; t < s.tris.size(); ++t) {
    const auto it = part_of_face.find(s.tri_face[t]);
    (it == part_of_face.end() ? rest : part_tris[it->second]).push_back(static_cast<int>(t));
  }
  // The pieces to unite: the rest's closed pieces (largest first), then each
  // part's: a part whose mesh is closed joins as its closed pieces, one at a
  // time (a component whose halves are closed shells that cross each other,
  // such as a T-tail's two halves through the fin, is united with itself
  // too); one whose mesh is open joins whole and fails, named. The rest's
  // open pieces (sheets) and the pieces that cannot take part (a mesh that
  // intersects itself) are kept as they are.
  std::vector<int> aside;
  std::vector<std::vector<int>> pieces = closed_pieces(s, rest, aside);
  const size_t rest_pieces = pieces.size();
  std::vector<int> part_of_piece(rest_pieces, -1);
  for (size_t p = 0; p < parts.size(); ++p) {
    std::vector<int> open;
    std::vector<std::vector<int>> closed = closed_pieces(s, part_tris[p], open);
    if (!open.empty() || closed.empty()) closed = {part_tris[p]};
    for (auto& tris : closed) pieces.push_back(std::move(tris)), part_of_piece.push_back(static_cast<int>(p));
  }

  // Target sizes at the nodes, for the band's edge length.
  const std::vector<double> node_h = target_sizes(s, h);

  std::unique_ptr<Tracked> base;
  std::set<int> base_nodes;
  // Per CAD face, the source triangles near a cut: uv hints for the projection.
  std::map<int, std::set<int>> near_cut;
  // A piece whose skin folds through itself waits until every other piece is
  // in the base: it joins only if its fold lies inside the base (the union
  // drops it there) and the union is then free of crossings.
  std::vector<size_t> waiting;
  // Source nodes moved to close a slot (close_gaps()): off their CAD faces.
  std::set<int> gap_moved;
  auto take = [&](size_t i, bool last_pass) {
    const bool is_part = i >= rest_pieces;
    auto fail = [&](const std::string& why) {
      if (is_part && out.failures[part_of_piece[i]].empty()) out.failures[part_of_piece[i]] = why;
      if (!is_part) ++out.rest_pieces_apart;
      aside.insert(aside.end(), pieces[i].begin(), pieces[i].end());
    };
    auto part = std::make_unique<Tracked>();
    std::string why;
    std::vector<FI> crossing;
    if (pieces[i].empty()) why = "it has no triangles";
    else if (!build(s, pieces[i], *part)) why = "its mesh is not manifold";
    for (VI v : part->m.vertices())
      if (why.empty() && base_nodes.count(part->node[v])) why = "its mesh shares nodes with the rest";
    if (why.empty()) why = unfit(*part, crossing);
    const bool folded = why == kCrossesItself;
    if (folded && !last_pass) return waiting.push_back(i);
    if (folded && base && inside_base(part->m, crossing, base->m)) why.clear();
    else if (folded) why = "its mesh intersects itself outside the other components";
    if (!why.empty()) return fail(why);
    for (VI v : part->m.vertices()) base_nodes.insert(part->node[v]);
    if (!base) {  // the start
      base = std::move(part);
      return;
    }
    auto before = std::make_unique<Tracked>(*base);
    std::set<int> moved_now;
    if (!folded) close_gaps(*part, *base, node_h, moved_now);
    // A union of volumes holds the larger of the two and no more than both:
    // a corefinement that went wrong (a folded skin) can give less, even
    // nothing, and still cross nowhere. A folded piece's own volume counts
    // its fold twice or not at all, so only the base's bounds it then.
    const double volume_base = PMP::volume(base->m), volume_part = PMP::volume(part->m);
    Follow follow;
    follow.s->a = base.get();
    follow.s->b = part.get();
    const CGAL::Bbox_3 part_box = PMP::bbox(part->m);
    auto cut_now = base->m.add_property_map<EI, bool>("e:cut_now", false).first;
    std::string wrong;
    try {
      if (!PMP::corefine_and_compute_union(base->m, part->m, base->m,
                                           PMP::parameters::visitor(follow).throw_on_self_intersection(!folded),
                                           PMP::parameters::default_values(),
                                           PMP::parameters::edge_is_constrained_map(cut_now)))
        wrong = "the corefinement of its mesh with the rest failed";
      else if (folded && crosses_within(base->m, part_box))
        wrong = "its mesh intersects itself, and its union with the rest does too";
      const double v = wrong.empty() ? PMP::volume(base->m) : 0.0;
      const double slack = 1e-6 * (volume_base + std::abs(volume_part));
      const double least = folded ? volume_base : std::max(volume_base, volume_part);
      const double most = volume_base + volume_part;
      if (wrong.empty() && v < least - slack)
        wrong = "its union with the rest would bound " + std::to_string(v) + ", less than " + std::to_string(least) +
                " (a corefinement gone wrong)";
      else if (wrong.empty() && !folded && v > most + slack)
        wrong = "its union with the rest would bound " + std::to_string(v) + ", more than both, " +
                std::to_string(most) + " (a corefinement gone wrong)";
    } catch (const std::exception&) {
      wrong = "the corefinement of its mesh with the rest failed";
    }
    if (!wrong.empty()) {
      for (VI v : part->m.vertices()) base_nodes.erase(part->node[v]);
      base = std::move(before);
      // A piece wholly inside the rest adds nothing to the union: its
      // triangles go, and it counts as united.
      Tracked whole;  // the piece as it was (the corefinement changed part)
      if (build(s, pieces[i], whole)) {
        const std::vector<FI> all(whole.m.faces().begin(), whole.m.faces().end());
        if (inside_base(whole.m, all, base->m)) return;
      }
      return fail(wrong);
    }
    gap_moved.insert(moved_now.begin(), moved_now.end());
    adopt_orphans(*base);
    for (EI e : base->m.edges())
      if (cut_now[e]) base->cut[e] = true;
    base->m.remove_property_map(cut_now);
  };
  for (size_t i = 0; i < pieces.size(); ++i) take(i, false);
  for (size_t i : waiting) take(i, true);
  for (size_t p = 0; p < parts.size(); ++p) out.united += out.failures[p].empty();
  out.gap_nodes_closed = static_cast<int>(gap_moved.size());
  if (!base) base = std::make_unique<Tracked>();
  renumber(*base);
  remesh_bands(*base, s, g, node_h, near_cut, out);
  base->m.collect_garbage();
  Mesh& m = base->m;

  // Every node the cut or the remesh made or moved goes onto its CAD faces.
  const double diag = [&] {
    Eigen::AlignedBox3d box;
    for (const Vec3& x : s.xyz) box.extend(x);
    return box.isEmpty() ? 1.0 : box.diagonal().norm();
  }();
  const NodeUV node_uv(s);
  FaceTriangles face_tris(s);
  std::map<std::pair<uint32_t, int>, Vec2> vertex_uv;  // (vertex, face) -> uv
  std::vector<Vec3> xyz(m.number_of_vertices());
  std::map<VI, std::vector<std::pair<int, Vec2>>> junction_faces;  // cut node -> (face, uv) on each of its surfaces
  std::vector<bool> on_cut(m.number_of_vertices(), false);
  for (EI e : m.edges())
    if (base->cut[e]) on_cut[m.vertex(e, 0)] = on_cut[m.vertex(e, 1)] = true;
  for (VI v : m.vertices()) xyz[v] = vec(m.point(v));
  auto displaced = [&](FI f) {
    if (gap_moved.empty() || base->tri[f] < 0) return false;
    for (int n : s.tris[base->tri[f]])
      if (gap_moved.count(n)) return true;
    return false;
  };
  // uv on source triangle t of the point of t nearest x; `dist` its distance.
  auto uv_on = [&](int t, const Vec3& x, double& dist) {
    const auto& tr = s.tris[t];
    const Vec3 w = TriangleBVH::closest_barycentric(x, s.xyz[tr[0]], s.xyz[tr[1]], s.xyz[tr[2]]);
    dist = (w[0] * s.xyz[tr[0]] + w[1] * s.xyz[tr[1]] + w[2] * s.xyz[tr[2]] - x).norm();
    return Vec2(w[0] * s.tri_uv[t][0] + w[1] * s.tri_uv[t][1] + w[2] * s.tri_uv[t][2]);
  };
  for (VI v : m.vertices()) {
    const int n = base->node[v];
    if (n >= 0 && (xyz[v] - s.xyz[n]).norm() == 0) continue;
    // Its faces: those of the triangles around it, but for a triangle moved
    // off its surface to close a slot.
    std::vector<int> faces;
    std::vector<FI> around;
    for (FI f : CGAL::faces_around_target(m.halfedge(v), m)) {
      if (f == Mesh::null_face()) continue;
      around.push_back(f);
      if (displaced(f)) continue;
      if (std::find(faces.begin(), faces.end(), base->face[f]) == faces.end()) faces.push_back(base->face[f]);
    }
    if (faces.empty() || faces.size() > 4) continue;
    // Starts: the source triangles of the triangles around the node, else
    // the nearest source triangle of that face near a cut, else the node's uv.
    std::vector<Vec2> uv(faces.size());
    bool started = true;
    for (size_t i = 0; i < faces.size() && started; ++i) {
      double best = HUGE_VAL, d;
      for (FI f : around)
        if (base->face[f] == faces[i] && base->tri[f] >= 0) {
          const Vec2 at = uv_on(base->tri[f], xyz[v], d);
          if (d < best) best = d, uv[i] = at;
        }
      if (best > 0)
        for (int t : near_cut[faces[i]]) {
          const Vec2 at = uv_on(t, xyz[v], d);
          if (d < best) best = d, uv[i] = at;
        }
      if (best == HUGE_VAL) {
        const Vec2* known = n >= 0 ? node_uv.find(n, faces[i]) : nullptr;
        const int t = known ? -1 : face_tris.nearest(faces[i], xyz[v]);
        if (known) uv[i] = *known;
        else if (t >= 0) uv[i] = uv_on(t, xyz[v], d);
        else started = false;
      }
    }
    if (!started) continue;
    // A start read off a source triangle's corners is linear in uv, off the
    // surface by about the triangle's chord height; where the surface's
    // parametrisation is not (a strip collapsed onto a trailing edge inside
    // the triangle), it maps a good part of the triangle away: the nearest
    // point of the whole face instead.
    double source = 0;  // the longest edge of the triangles around, or of their sources
    for (FI f : around) {
      if (base->tri[f] >= 0)
        for (int k = 0; k < 3; ++k) {
          const auto& tr = s.tris[base->tri[f]];
          source = std::max(source, (s.xyz[tr[k]] - s.xyz[tr[(k + 1) % 3]]).norm());
        }
      for (Mesh::Halfedge_index e : CGAL::halfedges_around_face(m.halfedge(f), m))
        source = std::max(source, (xyz[m.source(e)] - xyz[m.target(e)]).norm());
    }
    for (size_t i = 0; i < faces.size(); ++i) {
      auto off = [&](const Vec2& at) { return (g.eval_face(faces[i], at).p - xyz[v]).norm(); };
      const double start = off(uv[i]);
      if (start <= 0.1 * source) continue;
      Vec2 at = uv[i];
      if (!g.project_to_face(faces[i], xyz[v], at)) {  // Newton stalled: the whole face
        at = uv[i];
        if (!g.nearest_on_face(faces[i], xyz[v], at)) continue;
      }
      if (off(at) < start) uv[i] = at;
    }
    for (size_t i = 0; i < faces.size(); ++i) vertex_uv[{uint32_t(v), faces[i]}] = uv[i];
    // The move stays under half the shortest edge at the node and turns no
    // triangle over; where it would (surfaces meeting at a grazing angle),
    // the node keeps its place on the meshes.
    double shortest = HUGE_VAL;
    for (VI w : CGAL::vertices_around_target(m.halfedge(v), m)) shortest = std::min(shortest, (xyz[w] - xyz[v]).norm());
    Vec3 x = xyz[v];
    std::vector<Vec2> snapped = uv;
    const bool moved = snap(g, faces, snapped, x, 0.5 * shortest, 1e-13 * diag);
    bool flips = false;
    for (FI f : around) {
      std::array<Vec3, 3> before, after;
      int k = 0;
      for (VI w : CGAL::vertices_around_face(m.halfedge(f), m)) {
        before[k] = xyz[w];
        after[k++] = w == v ? x : xyz[w];
      }
      const Vec3 nb = (before[1] - before[0]).cross(before[2] - before[0]);
      const Vec3 na = (after[1] - after[0]).cross(after[2] - after[0]);
      flips = flips || !(na.dot(nb) > 0);
    }
    if (moved && !flips) {
      xyz[v] = x;
      for (size_t i = 0; i < faces.size(); ++i) vertex_uv[{uint32_t(v), faces[i]}] = snapped[i];
    }
    if (on_cut[v])
      for (size_t i = 0; i < faces.size(); ++i) junction_faces[v].push_back({faces[i], vertex_uv[{uint32_t(v), faces[i]}]});
  }

  // The new mesh: the source nodes keep their ids (moved ones their
  // classification); new nodes follow; unused nodes are dropped.
  SurfaceMesh r;
  r.failures = s.failures;
  r.stats = s.stats;
  std::vector<int> id(m.number_of_vertices(), -1);
  std::vector<Vec3> node_xyz = s.xyz, unsnapped = s.xyz;
  std::vector<int8_t> dim = s.node_dim;
  std::vector<int> entity = s.node_entity;
  for (VI v : m.vertices()) {
    const int n = base->node[v];
    if (n >= 0) {
      id[v] = n;
      node_xyz[n] = xyz[v];
      unsnapped[n] = vec(m.point(v));
      continue;
    }
    id[v] = static_cast<int>(node_xyz.size());
    node_xyz.push_back(xyz[v]);
    unsnapped.push_back(vec(m.point(v)));
    dim.push_back(2);
    int face = 0;
    for (FI f : CGAL::faces_around_target(m.halfedge(v), m))
      if (f != Mesh::null_face()) face = face ? std::min(face, base->face[f]) : base->face[f];
    entity.push_back(face);
    out.junction_nodes += on_cut[v];
  }
  std::vector<std::array<int, 3>> tris;
  std::vector<int> tri_face;
  std::vector<std::array<Vec2, 3>> tri_uv;
  for (FI f : m.faces()) {
    const int face = base->face[f], src = base->tri[f];
    std::array<int, 3> tr;
    std::array<Vec2, 3> uv;
    int k = 0;
    for (VI v : CGAL::vertices_around_face(m.halfedge(f), m)) {
      tr[k] = id[v];
      const int n = base->node[v];
      const auto known = vertex_uv.find({uint32_t(v), face});
      if (known != vertex_uv.end()) {
        uv[k] = known->second;
      } else if (src >= 0 && n >= 0 && std::find(s.tris[src].begin(), s.tris[src].end(), n) != s.tris[src].end()) {
        uv[k] = s.tri_uv[src][std::find(s.tris[src].begin(), s.tris[src].end(), n) - s.tris[src].begin()];
      } else if (const Vec2* at = n >= 0 ? node_uv.find(n, face) : nullptr) {
        uv[k] = *at;
      } else {
        // A start on the face's nearest source triangle, then the surface.
        double d;
        const int t = face_tris.nearest(face, node_xyz[tr[k]]);
        uv[k] = t >= 0 ? uv_on(t, node_xyz[tr[k]], d) : Vec2(0, 0);
        g.project_to_face(face, node_xyz[tr[k]], uv[k]);
      }
      ++k;
    }
    // On a periodic face, the corners in one period (the first corner's).
    for (int axis = 0; axis < 2; ++axis) {
      const double period = axis == 0 ? g.face_wrap_u(face) : g.face_wrap_v(face);
      if (period > 0)
        for (int j = 1; j < 3; ++j) uv[j][axis] += period * std::round((uv[0][axis] - uv[j][axis]) / period);
    }
    tris.push_back(tr);
    tri_face.push_back(face);
    tri_uv.push_back(uv);
  }
  for (int t : aside) tris.push_back(s.tris[t]), tri_face.push_back(s.tri_face[t]), tri_uv.push_back(s.tri_uv[t]);

  // Triangles by face, in their order; nodes renumbered in theirs.
  std::vector<int> order(tris.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return tri_face[a] < tri_face[b]; });
  std::vector<int> used(node_xyz.size(), -1);
  std::vector<Vec3> before_snap;
  for (const auto& tr : tris)
    for (int n : tr) used[n] = 0;
  for (size_t n = 0; n < used.size(); ++n)
    if (used[n] == 0) {
      used[n] = static_cast<int>(r.xyz.size());
      r.xyz.push_back(node_xyz[n]);
      before_snap.push_back(unsnapped[n]);
      r.node_dim.push_back(dim[n]);
      r.node_entity.push_back(entity[n]);
    }
  for (int t : order) {
    r.tris.push_back({used[tris[t][0]], used[tris[t][1]], used[tris[t][2]]});
    r.tri_face.push_back(tri_face[t]);
    r.tri_uv.push_back(tri_uv[t]);
  }
  out.crossing_pairs = keep_apart(r, before_snap);
  for (EI e : m.edges())
    if (base->cut[e]) out.junction.push_back({used[id[m.vertex(e, 0)]], used[id[m.vertex(e, 1)]]});
  // Each junction node's distance from each of its surfaces, as it ends.
  for (auto& [v, on] : junction_faces) count_junction_node(out, g, r.xyz[used[id[v]]], std::move(on), 1e-9 * diag);
  s = std::move(r);
  return out;
}

}  // namespace sizemesh
