// Flat disks, and whether a body passes through one (cad/actuator_disks.h).
#include "cad/actuator_disks.h"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAlgoAPI_Section.hxx>
#include <BRepBndLib.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepGProp.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <GeomLib_IsPlanarSurface.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>

#include <algorithm>

#include "cad/face_list.h"

namespace sizemesh::detail {

bool flat_disk(const TopoDS_Shape& s, double tol, gp_Pln& plane) {
  bool any = false;
  for (const auto& f : faces_of(s)) {
    const Handle(Geom_Surface) g = BRep_Tool::Surface(f);
    if (g.IsNull()) return false;
    GeomLib_IsPlanarSurface planar(g, tol);
    if (!planar.IsPlanar()) return false;
    const gp_Pln p = planar.Plan();
    if (!any) plane = p, any = true;
    else if (!plane.Axis().IsParallel(p.Axis(), 1e-6) || plane.Distance(p.Location()) > tol) return false;
  }
  if (!any) return false;
  GProp_GProps props;
  BRepGProp::SurfaceProperties(s, props);
  const gp_Pnt centre = props.CentreOfMass();
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(s, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  std::vector<double> r;
  for (int i = 1; i <= edge_faces.Extent(); ++i) {
    const TopoDS_Edge e = TopoDS::Edge(edge_faces.FindKey(i));
    if (edge_faces(i).Extent() != 1 || BRep_Tool::Degenerated(e)) continue;
    const BRepAdaptor_Curve c(e);
    for (int k = 0; k <= 8; ++k)
      r.push_back(centre.Distance(c.Value(c.FirstParameter() + (c.LastParameter() - c.FirstParameter()) * k / 8)));
  }
  if (r.empty()) return false;
  const double most = *std::max_element(r.begin(), r.end());
  return std::all_of(r.begin(), r.end(), [&](double d) { return d < 0.5 * most || d > 0.95 * most; });
}

bool pierced(const TopoDS_Shape& sheet, const gp_Pln& plane, const std::vector<TopoDS_Shape>& solids, double tol) {
  Bnd_Box sheet_box;
  BRepBndLib::Add(sheet, sheet_box);
  const FaceList faces = faces_of(sheet);
  for (const auto& solid : solids) {
    Bnd_Box box;
    BRepBndLib::Add(solid, box);
    if (box.IsOut(sheet_box)) continue;
    try {
      BRepAlgoAPI_Section section(solid, plane, false);
      section.Build();
      if (!section.IsDone()) continue;
      int points = 0;
      bool inside = true;
      for (TopExp_Explorer ex(section.Shape(), TopAbs_EDGE); ex.More() && inside; ex.Next()) {
        const BRepAdaptor_Curve c(TopoDS::Edge(ex.Current()));
        for (int i = 0; i <= 8 && inside; ++i, ++points) {
          const gp_Pnt p = c.Value(c.FirstParameter() + (c.LastParameter() - c.FirstParameter()) * i / 8);
          inside = std::any_of(faces.begin(), faces.end(), [&](const TopoDS_Face& f) {
            const TopAbs_State state = BRepClass_FaceClassifier(f, p, tol).State();
            return state == TopAbs_IN || state == TopAbs_ON;
          });
        }
      }
      if (inside && points > 0) return true;
    } catch (const Standard_Failure&) {
      continue;
    }
  }
  return false;
}

}  // namespace sizemesh::detail
