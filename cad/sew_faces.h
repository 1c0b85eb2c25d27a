// Faces sewn at a tolerance, their free curves counted: the trial by which the repair judges a change.
#pragma once

#include <BRepBuilderAPI_Sewing.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <atomic>
#include <memory>

#include "cad/face_list.h"

namespace sizemesh::detail {

// A sewing, its shape and free curves; `after(f)` is f as it is in the shape.
struct Sewn {
  TopoDS_Shape shape;
  int free_curves = 0;
  std::shared_ptr<BRepBuilderAPI_Sewing> sewing;
  TopoDS_Face after(const TopoDS_Face& f) const {
    return sewing->IsModified(f) ? TopoDS::Face(sewing->Modified(f)) : f;
  }
};

// The faces sewn at `tol`; abandoned (its result of no use) once `stop` is set.
Sewn sew(const FaceList& faces, double tol, const std::atomic<bool>* stop = nullptr);

}  // namespace sizemesh::detail
