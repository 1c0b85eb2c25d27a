// The sewn shape's components and their description (cad/components.h).
#include "cad/components.h"

#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <TopExp_Explorer.hxx>

#include <cmath>

#include "cad/face_list.h"
#include "cad/occt_model.h"

namespace sizemesh::detail {

Component describe(const TopoDS_Shape& s, const TopTools_DataMapOfShapeReal& area) {
  Component c;
  const FaceList faces = faces_of(s);
  c.faces = static_cast<int>(faces.size());
  c.free_curves = count_free_curves(s);
  c.closed = c.free_curves == 0 && (s.ShapeType() == TopAbs_SOLID || s.ShapeType() == TopAbs_SHELL);
  for (const auto& f : faces) {
    if (area.IsBound(f)) {
      c.area += area(f);
      continue;
    }
    GProp_GProps g;
    BRepGProp::SurfaceProperties(f, g);
    c.area += std::abs(g.Mass());
  }
  Bnd_Box box;
  BRepBndLib::Add(s, box, false);
  if (!box.IsVoid()) {
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    c.bbox_min = {x0, y0, z0};
    c.bbox_max = {x1, y1, z1};
  }
  return c;
}

std::vector<TopoDS_Shape> components_of(const TopoDS_Shape& shape) {
  std::vector<TopoDS_Shape> out;
  for (TopExp_Explorer ex(shape, TopAbs_SOLID); ex.More(); ex.Next()) out.push_back(ex.Current());
  for (TopExp_Explorer ex(shape, TopAbs_SHELL, TopAbs_SOLID); ex.More(); ex.Next()) out.push_back(ex.Current());
  for (TopExp_Explorer ex(shape, TopAbs_FACE, TopAbs_SHELL); ex.More(); ex.Next()) out.push_back(ex.Current());
  return out;
}

}  // namespace sizemesh::detail
