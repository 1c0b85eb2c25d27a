// Queries on shapes shared by loading and preparation: free curves, a step's validity, solids, boxes, areas.
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepLib.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>

#include <cmath>
#include <string>

#include "cad/occt_model.h"

namespace sizemesh {

// Curves bounding exactly one face side (seams and degenerate curves excluded).
int count_free_curves(const TopoDS_Shape& shape) {
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  int free = 0;
  for (int i = 1; i <= edge_faces.Extent(); ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(edge_faces.FindKey(i));
    if (BRep_Tool::Degenerated(e)) continue;
    const auto& faces = edge_faces(i);
    if (faces.Extent() == 1 && !BRep_Tool::IsClosed(e, TopoDS::Face(faces.First()))) ++free;
  }
  return free;
}

bool step_keeps_shape_valid(const TopoDS_Shape& before, const TopoDS_Shape& after) {
  if (count_free_curves(before) == 0 && count_free_curves(after) != 0) return false;
  TopTools_IndexedMapOfShape old;
  TopExp::MapShapes(before, TopAbs_FACE, old);
  TopoDS_Compound fresh;
  BRep_Builder b;
  b.MakeCompound(fresh);
  bool any = false;
  for (TopExp_Explorer ex(after, TopAbs_FACE); ex.More(); ex.Next())
    if (!old.Contains(ex.Current())) b.Add(fresh, ex.Current()), any = true;
  return !any || BRepCheck_Analyzer(fresh, true, true).IsValid();
}

TopoDS_Solid solid_from_shell(const TopoDS_Shell& shell) {
  BRepBuilderAPI_MakeSolid make(shell);
  if (!make.IsDone()) return {};
  TopoDS_Solid solid = make.Solid();
  BRepLib::OrientClosedSolid(solid);
  return solid;
}

double bbox_diagonal(const TopoDS_Shape& shape, Vec3& lo, Vec3& hi) {
  Bnd_Box box;
  BRepBndLib::Add(shape, box, false);
  if (box.IsVoid()) throw Error("the shape has no extent");
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  lo = {x0, y0, z0};
  hi = {x1, y1, z1};
  const double diag = (hi - lo).norm();
  // Corrupt coordinates, or a model no mesh size can be derived from.
  if (!std::isfinite(diag) || !(diag > 1e-9) || diag > 1e12)
    throw Error("the model's bounding box is unusable (diagonal " + std::to_string(diag) +
                " file units; valid models span 1e-9 to 1e12)");
  return diag;
}

double face_area_exact(const TopoDS_Shape& face, double relative_eps) {
  GProp_GProps props;
  if (relative_eps > 0) BRepGProp::SurfaceProperties(face, props, relative_eps);
  else BRepGProp::SurfaceProperties(face, props);
  return std::abs(props.Mass());
}

}  // namespace sizemesh
