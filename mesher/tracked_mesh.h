// The mesh-level union's working mesh: a CGAL mesh that tracks source triangles, CAD faces and nodes.
//
// Internal to the mesh-level union (mesher/mesh_union.cpp and its steps in
// corefine_tracking, close_gaps, remesh_bands and union_to_surface). The
// checks say whether a piece can take part in a union of volumes.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Surface_mesh.h>

#include <string>
#include <vector>

#include "mesher/surface_mesh.h"

namespace sizemesh::mesh_union_detail {

namespace PMP = CGAL::Polygon_mesh_processing;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using VI = Mesh::Vertex_index;
using FI = Mesh::Face_index;
using EI = Mesh::Edge_index;

inline Vec3 vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }
inline Point point(const Vec3& v) { return Point(v.x(), v.y(), v.z()); }

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
bool build(const SurfaceMesh& s, const std::vector<int>& ids, Tracked& t);

constexpr const char* kCrossesItself = "its mesh intersects itself";

// Why `t` cannot take part in a union of volumes; empty when it can (it is
// then oriented outward). Its triangles that cross each other go to `crossing`.
std::string unfit(Tracked& t, std::vector<FI>& crossing);

// True when triangles of m within `box` intersect each other: where a piece
// joined, the rest of m being as it was.
bool crosses_within(const Mesh& m, const CGAL::Bbox_3& box);

// True when every corner of the triangles `tris` of `m` lies strictly inside
// the closed mesh `base`: a fold there, or the whole piece, is dropped by the union.
bool inside_base(const Mesh& m, const std::vector<FI>& tris, const Mesh& base);

}  // namespace sizemesh::mesh_union_detail
