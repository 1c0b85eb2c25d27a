// Sewn edges on planes whose tolerance grew past the sewing's own, rebuilt
// exactly (mend_sewn_edges, cad/occt_model.h).
//
// Sewing keeps one of two coincident edges' 3D curves and makes the other
// face's curve in its parameters follow it by an approximate
// reparametrisation. OpenVSP writes a cap's two halves with their common
// chord line parametrised in opposite directions and with different spacing;
// that reparametrisation is far from linear, the approximation misses, and
// the edge's tolerance becomes the largest miss: a sizeable part of the wing's
// chord. A general fuse then finds everything within that tolerance in
// contact. On a plane, the curve on each face projected afresh from the kept
// 3D curve is same-parameter by construction.
#include <BRepLib.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Curve.hxx>
#include <TopLoc_Location.hxx>
#include <ShapeBuild_Edge.hxx>
#include <ShapeFix_ShapeTolerance.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>

#include <vector>

#include "cad/occt_model.h"

namespace sizemesh {

int mend_sewn_edges(const TopoDS_Shape& shape, double tol) {
  if (shape.IsNull()) return 0;
  bool wide = false;
  for (TopExp_Explorer ex(shape, TopAbs_EDGE); ex.More() && !wide; ex.Next())
    wide = BRep_Tool::Tolerance(TopoDS::Edge(ex.Current())) > 100 * tol;
  if (!wide) return 0;
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  BRep_Builder b;
  int mended = 0;
  for (int i = 1; i <= edge_faces.Extent(); ++i) {
    const TopoDS_Edge e = TopoDS::Edge(edge_faces.FindKey(i));
    const double was = BRep_Tool::Tolerance(e);
    if (!(was > 100 * tol) || BRep_Tool::Degenerated(e) || edge_faces(i).Extent() < 1 || edge_faces(i).Extent() > 2)
      continue;
    // Between planes, each face's curve is projected afresh from the kept
    // 3D curve. With a curved face, the 3D curve is rebuilt from that face's
    // curve first (OpenVSP's root cap folded onto its chord, sewn to a
    // planform plane whose chord is parametrised evenly: the cap's curve is
    // exact, the line kept by the sewing is not its parametrisation), then
    // the planes' curves projected from it. Kept only when much tighter: a
    // curve projected onto a B-spline that collapses near the edge's ends
    // comes out worse for the mesher than the one sewn.
    TopoDS_Face curved;
    int n_curved = 0;
    for (const auto& f : edge_faces(i))
      if (BRepAdaptor_Surface(TopoDS::Face(f), false).GetType() != GeomAbs_Plane) curved = TopoDS::Face(f), ++n_curved;
    if (n_curved > 1 || (n_curved == 0 && edge_faces(i).Extent() != 2)) continue;
    // The curves as sewn, put back when no better ones come.
    struct Kept {
      TopoDS_Face face;
      Handle(Geom2d_Curve) curve;
      double first = 0, last = 0;
    };
    std::vector<Kept> kept;
    for (const auto& f : edge_faces(i)) {
      if (TopoDS::Face(f).IsSame(curved)) continue;
      Kept k{TopoDS::Face(f), nullptr};
      k.curve = BRep_Tool::CurveOnSurface(e, k.face, k.first, k.last);
      kept.push_back(k);
    }
    TopLoc_Location loc;
    double c_first = 0, c_last = 0;
    const Handle(Geom_Curve) kept_3d = BRep_Tool::Curve(e, loc, c_first, c_last);
    TopoDS_Vertex v0, v1;
    TopExp::Vertices(e, v0, v1);
    const double was_v0 = v0.IsNull() ? 0 : BRep_Tool::Tolerance(v0);
    const double was_v1 = v1.IsNull() ? 0 : BRep_Tool::Tolerance(v1);
    const ShapeFix_ShapeTolerance set;
    bool ok = true;
    try {
      for (const Kept& k : kept) ShapeBuild_Edge().RemovePCurve(e, k.face);
      if (!curved.IsNull()) {
        b.UpdateEdge(e, Handle(Geom_Curve)(), TopLoc_Location(), was);
        ok = BRepLib::BuildCurve3d(e, tol) && !BRep_Tool::Curve(e, c_first, c_last).IsNull();
      }
      for (const Kept& k : kept) {
        TopTools_ListOfShape one;
        one.Append(e);
        BRepLib::BuildPCurveForEdgesOnPlane(one, k.face);
        double f0, f1;
        ok = ok && !BRep_Tool::CurveOnSurface(e, k.face, f0, f1).IsNull();
      }
      if (ok) {
        // Tolerances only ever grow through BRep_Builder: set them, then let
        // SameParameter and UpdateTolerances raise what the geometry needs.
        set.SetTolerance(e, tol, TopAbs_EDGE);
        if (!v0.IsNull()) set.SetTolerance(v0, tol, TopAbs_VERTEX);
        if (!v1.IsNull()) set.SetTolerance(v1, tol, TopAbs_VERTEX);
        b.SameRange(e, false);
        b.SameParameter(e, false);
        BRepLib::SameParameter(e, tol);
        ok = BRep_Tool::Tolerance(e) < (curved.IsNull() ? was : 0.1 * was);
      }
    } catch (const Standard_Failure&) {
      ok = false;
    }
    if (ok) {
      ++mended;
      continue;
    }
    if (!curved.IsNull()) b.UpdateEdge(e, kept_3d, loc, was), b.Range(e, c_first, c_last, true);
    for (const Kept& k : kept) {
      ShapeBuild_Edge().RemovePCurve(e, k.face);
      if (!k.curve.IsNull()) b.UpdateEdge(e, k.curve, k.face, was), b.Range(e, k.face, k.first, k.last);
    }
    set.SetTolerance(e, was, TopAbs_EDGE);
    if (!v0.IsNull()) set.SetTolerance(v0, was_v0, TopAbs_VERTEX);
    if (!v1.IsNull()) set.SetTolerance(v1, was_v1, TopAbs_VERTEX);
    b.SameParameter(e, true);
  }
  if (mended > 0) BRepLib::UpdateTolerances(shape, false);
  return mended;
}

}  // namespace sizemesh
