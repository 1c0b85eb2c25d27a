// Closed edges shorter than the sewing tolerance dropped (drop_small_loops, cad/small_loops.h).
#include "cad/small_loops.h"

#include <BRepAdaptor_Curve.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRep_Tool.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <ShapeBuild_ReShape.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

#include "cad/face_list.h"

namespace sizemesh::detail {

TopoDS_Shape drop_small_loops(const TopoDS_Shape& shape, double tol, const Follow& follow, int& count) {
  count = 0;
  Handle(ShapeBuild_ReShape) reshape = new ShapeBuild_ReShape;
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(shape, TopAbs_EDGE, edges);
  try {
    for (int i = 1; i <= edges.Extent(); ++i) {
      const TopoDS_Edge& e = TopoDS::Edge(edges(i));
      TopoDS_Vertex v0, v1;
      TopExp::Vertices(e, v0, v1);
      if (BRep_Tool::Degenerated(e) || v0.IsNull() || !v0.IsSame(v1)) continue;
      const BRepAdaptor_Curve c(e);
      if (!c.Is3DCurve() || !(GCPnts_AbscissaPoint::Length(c) < tol)) continue;
      reshape->Remove(e);
      ++count;
    }
    if (count == 0) return shape;
    const TopoDS_Shape result = reshape->Apply(shape);
    if (result.IsNull() || !BRepCheck_Analyzer(result).IsValid()) return count = 0, shape;
    for (const auto& f : faces_of(shape)) {
      const TopoDS_Shape now = reshape->Apply(f);
      if (!now.IsNull() && now.ShapeType() == TopAbs_FACE && !now.IsSame(f)) follow(f, TopoDS::Face(now));
    }
    return result;
  } catch (const Standard_Failure&) {
    count = 0;
    return shape;
  }
}

}  // namespace sizemesh::detail
