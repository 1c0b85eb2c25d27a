// The tracked mesh kept through CGAL's corefinement: its visitor, orphaned triangles, a run-independent numbering.
//
// Internal to the mesh-level union (mesher/mesh_union.cpp).
#pragma once

#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include <memory>

#include "mesher/tracked_mesh.h"

namespace sizemesh::mesh_union_detail {

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

// Triangles the corefinement made without telling its visitor (it splits a
// triangle whose corners all lie on the other mesh, where two surfaces touch
// in a plane, by plain Euler operations) take the source triangle and CAD
// face of a neighbour in the plane of the triangle they were split from, else
// of any neighbour that has one.
void adopt_orphans(Tracked& t);

// t renumbered in an order that depends on the geometry alone: vertices by
// their coordinates, triangles by their vertices. CGAL's corefinement breaks
// ties between boxes by their heap address, so its new vertices and faces
// come in an order that changes from run to run, and the band remesh, which
// visits them in order, would give a different mesh each time.
void renumber(Tracked& t);

}  // namespace sizemesh::mesh_union_detail
