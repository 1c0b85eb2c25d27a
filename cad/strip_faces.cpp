// Strip faces too narrow to keep their corners, collapsed to one curve
// (collapse_strips, cad/occt_model.h).
//
// A face that is a strip between two long curves, narrower everywhere than
// twice the sewing tolerance (the blunt trailing edge of a thin fin, say),
// cannot keep four corners: sewing merges each end's two vertices, so its
// short curves become loops on one vertex, and the fuse does the same where
// the strip meets another body. A front cannot close such a face: it lays
// triangles over each other across it and the neighbour that shares the
// loop. The strip is removed and its two long curves become one curve shared
// by the faces on either side (ShapeFix_FixSmallFace's strip replacement);
// the surface moves by at most the strip's width, far below any element.
#include <BRep_Tool.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <ShapeAnalysis_CheckSmallFace.hxx>
#include <ShapeBuild_ReShape.hxx>
#include <ShapeFix_Edge.hxx>
#include <ShapeFix_FixSmallFace.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>

#include <utility>
#include <vector>

#include "cad/occt_model.h"

namespace sizemesh {
namespace {

// Every edge of `shape` given a pcurve on each face that uses it and lacks
// one (the merged curve carries at most one side's) and made same-parameter,
// its tolerance and its vertices' raised to the distance between the two
// sides; false when a pcurve cannot be made.
bool add_missing_pcurves(const TopoDS_Shape& shape) {
  TopTools_IndexedDataMapOfShapeListOfShape faces_of;
  TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, faces_of);
  for (int i = 1; i <= faces_of.Extent(); ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(faces_of.FindKey(i));
    bool added = false;
    for (const TopoDS_Shape& f : faces_of(i)) {
      double first = 0, last = 0;
      if (!BRep_Tool::CurveOnSurface(e, TopoDS::Face(f), first, last).IsNull()) continue;
      if (!ShapeFix_Edge().FixAddPCurve(e, TopoDS::Face(f), false)) return false;
      added = true;
    }
    if (!added && BRep_Tool::SameParameter(e)) continue;
    ShapeFix_Edge fix;
    fix.FixSameParameter(e);
    for (const TopoDS_Shape& f : faces_of(i)) fix.FixVertexTolerance(e, TopoDS::Face(f));
  }
  return true;
}

}  // namespace

TopoDS_Shape collapse_strips(const TopoDS_Shape& shape, double width,
                             const std::function<void(const TopoDS_Face&, const TopoDS_Face&)>& follow,
                             int& collapsed) {
  if (shape.IsNull() || !(width > 0)) return shape;
  try {
    TopTools_IndexedMapOfShape faces;
    TopExp::MapShapes(shape, TopAbs_FACE, faces);
    ShapeFix_FixSmallFace fix;
    fix.Init(shape);
    fix.SetPrecision(width);
    fix.SetMaxTolerance(width);
    Handle(ShapeBuild_ReShape) context = new ShapeBuild_ReShape;
    fix.SetContext(context);
    int removed = 0;
    for (int i = 1; i <= faces.Extent(); ++i) {
      TopoDS_Face f = TopoDS::Face(faces(i));
      TopoDS_Edge long_a, long_b;
      if (!ShapeAnalysis_CheckSmallFace().CheckStripFace(f, long_a, long_b, width)) continue;
      if (fix.ReplaceInCaseOfStrip(f, long_a, long_b, width) && fix.RemoveFacesInCaseOfStrip(f)) ++removed;
    }
    if (removed == 0) return shape;
    const TopoDS_Shape result = context->Apply(shape);
    if (result.IsNull() || !add_missing_pcurves(result)) return shape;
    if (count_free_curves(result) > count_free_curves(shape)) return shape;
    // Only the faces beside a strip changed: each must still be valid.
    std::vector<std::pair<TopoDS_Face, TopoDS_Face>> changed;
    for (int i = 1; i <= faces.Extent(); ++i) {
      const TopoDS_Shape now = context->Value(faces(i));
      if (now.IsNull() || now.IsSame(faces(i))) continue;
      if (now.ShapeType() != TopAbs_FACE || !BRepCheck_Analyzer(now).IsValid()) return shape;
      changed.emplace_back(TopoDS::Face(faces(i)), TopoDS::Face(now));
    }
    for (const auto& [from, to] : changed) follow(from, to);
    collapsed += removed;
    return result;
  } catch (const Standard_Failure&) {
    return shape;
  }
}

}  // namespace sizemesh
