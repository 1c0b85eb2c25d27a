// The imprint of open components on the bodies by the general fuse (imprint_sheets).
#pragma once

#include <TopoDS_Shape.hxx>

#include <vector>

#include "cad/occt_model.h"

namespace sizemesh::detail {

// The general fuse of the bodies and the sheets (BOPAlgo_Builder): every curve
// where a sheet meets a body or another sheet is shared by the faces on both
// sides, and sheet pieces inside a body (or lying on its surface) are
// dropped. Returns the kept faces as a compound, oriented as in the result,
// or a null shape when the fuse fails. Within what is left of `deadline`,
// whose work the fuse adds to.
TopoDS_Shape imprint_sheets(const std::vector<TopoDS_Shape>& bodies, const std::vector<TopoDS_Shape>& sheets,
                            double tol, WorkBudget& deadline, const Follow& follow, Preparation& info);

}  // namespace sizemesh::detail
