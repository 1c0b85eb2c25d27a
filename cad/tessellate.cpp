// BRepMesh tessellation of the model, copied out of OCCT's triangulations
// (cad/tessellate.h).
#include "cad/tessellate.h"

#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include <algorithm>
#include <string>

#include "cad/occt_model.h"

namespace sizemesh {
namespace {

void run_brepmesh(const Model& model, const BackgroundOptions& options) {
  const double diag = model.info().diagonal();
  const double angle = options.angle_deg * kPi / 180.0;
  const double far = model.info().domain.size;
  if (far > 0) {
    // The far field, many body diagonals across, at a deflection relative
    // to its own size; then the rest (the body and the symmetry plane,
    // which share curves) at the body's. Curves the far field shares with
    // the symmetry plane keep their first discretisation.
    TopoDS_Compound outer, rest;
    BRep_Builder b;
    b.MakeCompound(outer);
    b.MakeCompound(rest);
    for (int f = 1; f <= model.num_faces(); ++f)
      b.Add(model.boundary(f) == Boundary::Farfield ? outer : rest, model.impl().faces(f));
    BRepMesh_IncrementalMesh(outer, 10 * options.deflection_rel * far, false, angle, true);
    BRepMesh_IncrementalMesh(rest, options.deflection_rel * diag, false, angle, true);
  } else {
    BRepMesh_IncrementalMesh(model.impl().shape, options.deflection_rel * diag, false, angle, true);
  }
}

void copy_face(const Model::Impl& m, int f, FaceTessellation& out) {
  const TopoDS_Face face = TopoDS::Face(m.faces(f).Oriented(TopAbs_FORWARD));
  TopLoc_Location loc;
  Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
  if (tri.IsNull() || tri->NbTriangles() == 0 || !tri->HasUVNodes()) return;
  const int n = tri->NbNodes();
  out.xyz.resize(n);
  out.uv.resize(n);
  for (int i = 0; i < n; ++i) {
    const gp_Pnt p = tri->Node(i + 1).Transformed(loc.Transformation());
    out.xyz[i] = Vec3(p.X(), p.Y(), p.Z());
    const gp_Pnt2d uv = tri->UVNode(i + 1);
    out.uv[i] = Vec2(uv.X(), uv.Y());
  }
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
    Handle(Poly_PolygonOnTriangulation) poly = BRep_Tool::PolygonOnTriangulation(e, tri, loc);
    if (poly.IsNull()) continue;
    FaceTessellation::CurveUse use;
    use.curve = m.edges.FindIndex(e);
    const OcctCurve& cd = m.curve_data[use.curve - 1];
    const int k = poly->NbNodes();
    const TColStd_Array1OfInteger& nodes = poly->Nodes();
    const bool has_params = poly->HasParameters();
    for (int i = 0; i < k; ++i) {
      use.nodes.push_back(nodes(nodes.Lower() + i) - 1);
      use.t.push_back(has_params ? poly->Parameter(i + 1) : cd.t0 + (cd.t1 - cd.t0) * i / std::max(1, k - 1));
    }
    out.curves.push_back(std::move(use));
  }
  out.tris.resize(tri->NbTriangles());
  for (int t = 1; t <= tri->NbTriangles(); ++t) {
    int a, b, c;
    tri->Triangle(t).Get(a, b, c);
    out.tris[t - 1] = {a - 1, b - 1, c - 1};
  }
}

}  // namespace

Tessellation tessellate(const Model& model, const BackgroundOptions& options) {
  if (!(options.deflection_rel > 0) || !(options.angle_deg > 0))
    throw Error("tessellation deflection and angle must be positive");
  try {
    run_brepmesh(model, options);
  } catch (const Standard_Failure& e) {
    throw Error(std::string("tessellation failed: ") + e.GetMessageString());
  }
  Tessellation out;
  out.faces.resize(model.num_faces());
  for (int f = 1; f <= model.num_faces(); ++f) copy_face(model.impl(), f, out.faces[f - 1]);
  return out;
}

}  // namespace sizemesh
