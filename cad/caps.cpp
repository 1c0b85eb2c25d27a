// Planar caps over flat free loops (cad/occt_model.h).
//
// OpenVSP and pyGeo export wings and struts without the flat face that
// closes a tip or a root: the free curves of such a component form a closed
// loop on a plane. A planar face on that loop closes the component, so it
// takes part in the union (a strut's root cap then lies inside the wing and
// disappears with it). A loop on the plane of a half model (a coordinate
// plane through 0 at a side of the model's box, where the root of a half
// wing lies) is the symmetry plane's to close: it is capped only when the
// run cuts at that plane, and counted otherwise.
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepLib_FindSurface.hxx>
#include <BRep_Tool.hxx>
#include <Geom_Plane.hxx>
#include <ShapeAnalysis_FreeBounds.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_HSequenceOfShape.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Pln.hxx>

#include <cmath>

#include "cad/occt_model.h"

namespace sizemesh {
namespace {

// The free edges of `shape` (bounding one face side; seams and degenerate edges excluded).
Handle(TopTools_HSequenceOfShape) free_edges(const TopoDS_Shape& shape) {
  Handle(TopTools_HSequenceOfShape) out = new TopTools_HSequenceOfShape;
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  for (int i = 1; i <= edge_faces.Extent(); ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(edge_faces.FindKey(i));
    if (BRep_Tool::Degenerated(e)) continue;
    const auto& faces = edge_faces(i);
    if (faces.Extent() == 1 && !BRep_Tool::IsClosed(e, TopoDS::Face(faces.First()))) out->Append(edge_faces.FindKey(i));
  }
  return out;
}

// The axis (0-2) of the half-model plane the loop lies on, or -1.
int loop_on_plane(const Handle(Geom_Plane)& plane, const TopoDS_Wire& wire, const HalfModelPlanes& half) {
  const gp_Dir n = plane->Axis().Direction();
  for (int a = 0; a < 3; ++a) {
    if (!half.candidate[a] || std::abs(n.Coord(a + 1)) < 1 - 1e-9) continue;
    bool on = true;
    for (TopExp_Explorer ex(wire, TopAbs_VERTEX); ex.More() && on; ex.Next())
      on = std::abs(BRep_Tool::Pnt(TopoDS::Vertex(ex.Current())).Coord(a + 1)) <= half.tolerance;
    if (on) return a;
  }
  return -1;
}

}  // namespace

HalfModelPlanes half_model_planes(const Vec3& lo, const Vec3& hi, double tol) {
  HalfModelPlanes h;
  h.tolerance = std::max(10 * tol, 1e-6 * (hi - lo).norm());
  for (int a = 0; a < 3; ++a) h.candidate[a] = std::abs(lo[a]) <= h.tolerance || std::abs(hi[a]) <= h.tolerance;
  return h;
}

Caps planar_caps(const TopoDS_Shape& shape, double tol, const HalfModelPlanes& half, int cap_axis) {
  Caps out;
  Handle(TopTools_HSequenceOfShape) edges, wires;
  try {
    edges = free_edges(shape);
    if (edges->IsEmpty()) return out;
    ShapeAnalysis_FreeBounds::ConnectEdgesToWires(edges, tol, Standard_False, wires);
  } catch (const Standard_Failure&) {
    return out;
  }
  // Each loop on its own: one that fails (a loop of no area, on a line) does
  // not keep the others open.
  for (int i = 1; i <= wires->Length(); ++i) {
    try {
      const TopoDS_Wire wire = TopoDS::Wire(wires->Value(i));
      TopoDS_Vertex first, last;
      TopExp::Vertices(wire, first, last);
      if (first.IsNull() || !first.IsSame(last)) continue;  // not a closed loop
      BRepLib_FindSurface find(wire, tol, Standard_True);
      if (!find.Found()) continue;
      const Handle(Geom_Plane) plane = Handle(Geom_Plane)::DownCast(find.Surface());
      if (plane.IsNull()) continue;
      const int axis = loop_on_plane(plane, wire, half);
      if (axis >= 0 && axis != cap_axis) {
        ++out.half_model_loops;
        out.half_model_axis = axis;
        continue;
      }
      BRepBuilderAPI_MakeFace make(plane->Pln(), wire, Standard_True);
      if (make.IsDone()) out.faces.push_back(make.Face());
    } catch (const Standard_Failure&) {
      continue;
    }
  }
  return out;
}

}  // namespace sizemesh
