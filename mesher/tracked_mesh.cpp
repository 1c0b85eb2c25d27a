// The mesh-level union's working mesh built from a SurfaceMesh, and its checks for a union of volumes.
#include "mesher/tracked_mesh.h"

#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <boost/iterator/function_output_iterator.hpp>
#include <set>
#include <unordered_map>

namespace sizemesh::mesh_union_detail {
namespace {

// The triangles of m that cross another triangle of m.
std::vector<FI> crossing_triangles(const Mesh& m) {
  std::set<FI> out;
  PMP::self_intersections(m, boost::make_function_output_iterator([&out](const std::pair<FI, FI>& p) {
                            out.insert(p.first);
                            out.insert(p.second);
                          }));
  return {out.begin(), out.end()};
}

}  // namespace

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

bool crosses_within(const Mesh& m, const CGAL::Bbox_3& box) {
  std::vector<FI> near;
  for (FI f : m.faces())
    if (CGAL::do_overlap(PMP::face_bbox(f, m), box)) near.push_back(f);
  return PMP::does_self_intersect(near, m);
}

bool inside_base(const Mesh& m, const std::vector<FI>& tris, const Mesh& base) {
  const CGAL::Side_of_triangle_mesh<Mesh, K> side(base);
  for (FI f : tris)
    for (VI v : CGAL::vertices_around_face(m.halfedge(f), m))
      if (side(m.point(v)) != CGAL::ON_BOUNDED_SIDE) return false;
  return true;
}

}  // namespace sizemesh::mesh_union_detail
