// The repair of one open component, judged by re-sewing it (repair_component).
//
// Repair works per open component and judges every change by re-sewing it:
//  - coincident face pairs (two halves of a body that both carry the cap
//    between them) are taken out when that leaves no more free curves;
//  - faces with a free curve are taken out one at a time, best first, while
//    each removal lowers the free-curve count; the result is kept only when
//    the component closes, and each face taken out must lie inside the closed
//    volume (an internal sheet such as a wing's planform plane), otherwise it
//    stays as a sheet of its own. A component that does not close is kept as
//    it was read: nothing is lost.
#pragma once

#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <utility>
#include <vector>

#include "cad/face_list.h"
#include "cad/occt_model.h"
#include "cad/sew_faces.h"

namespace sizemesh::detail {

// The repair of one open component. A null `closed` on return means "keep
// the component as it was".
struct Repair {
  TopoDS_Shape closed;    // the closed, sewn component (a shell), or null
  TopoDS_Shape half_open;  // or a half model's shell, open only on its plane
  Sewn sewn;              // the sewing that made it
  FaceList kept;          // faces of `closed`, before that sewing
  FaceList sheets;        // faces taken out that lie outside the component's volume
  std::vector<std::pair<TopoDS_Face, TopoDS_Face>> split;  // (face read, piece) of faces split at a slit
  int duplicates = 0, internal = 0, caps = 0;
  int half_model_axis = -1;  // the half-model plane its free loops lie on
  // CPU seconds of the sewing trials run on other threads whose results were
  // used (cad/deadline.h's WorkBudget counts them).
  double helper_work = 0;
};

// The repair of the faces `read` of one component (`component_diagonal`: the
// size of its box); loops on a half-model plane are capped only when its axis
// is `cap_axis` (planar_caps).
Repair repair_component(const FaceList& read, double tol, double component_diagonal, const HalfModelPlanes& half,
                        int cap_axis);

}  // namespace sizemesh::detail
