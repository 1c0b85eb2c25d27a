// The bands along the union's cuts remeshed (CGAL isotropic remeshing), one size class at a time.
#include "mesher/remesh_bands.h"

#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/box_intersection_d.h>

#include <boost/iterator/function_output_iterator.hpp>
#include <algorithm>
#include <cmath>

namespace sizemesh::mesh_union_detail {
namespace {

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

}  // namespace

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

}  // namespace sizemesh::mesh_union_detail
