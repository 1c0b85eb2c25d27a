// Shapes put together with OCCT and the meshes checked on them, shared by the geometry preparation's tests.
#pragma once

#include <catch2/catch.hpp>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Pnt.hxx>

#include <initializer_list>
#include <utility>

#include "cad/model.h"
#include "core/size_field.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"

namespace sizemesh::test {

inline TopoDS_Compound compound(std::initializer_list<TopoDS_Shape> parts) {
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  for (const auto& s : parts) b.Add(c, s);
  return c;
}

// Planar face through four corners.
inline TopoDS_Shape quad(gp_Pnt a, gp_Pnt b, gp_Pnt c, gp_Pnt d) {
  return BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakePolygon(a, b, c, d, true).Wire(), true).Face();
}

inline double total_area(const Geometry& g) {
  double a = 0;
  for (int f = 1; f <= g.num_faces(); ++f) a += g.face_area(f);
  return a;
}

// Meshes the model at size h: every face, nothing inverted or crossing.
inline std::pair<SurfaceMesh, MeshQuality> mesh_checked(const Model& model, double h) {
  const UniformSize size(h);
  SurfaceMesh m = mesh_surface(model, size);
  REQUIRE(m.failures.empty());
  MeshQuality q = mesh_quality(m, model, size);
  CHECK(q.inverted == 0);
  CHECK(q.self_intersections == 0);
  return {std::move(m), std::move(q)};
}

// ... and a closed, consistently oriented surface.
inline SurfaceMesh mesh_closed(const Model& model, double h) {
  auto [m, q] = mesh_checked(model, h);
  CHECK(q.boundary_edges == 0);
  CHECK(q.nonmanifold_edges == 0);
  CHECK(q.orientation_conflicts == 0);
  return m;
}

}  // namespace sizemesh::test
