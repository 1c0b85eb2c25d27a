// Closed edges shorter than the sewing tolerance dropped from their wires (drop_small_loops).
#pragma once

#include <TopoDS_Shape.hxx>

#include "cad/occt_model.h"

namespace sizemesh::detail {

// Closed edges shorter than the sewing tolerance dropped from their wires:
// what sewing leaves where the ends of two curves met a few tolerances
// apart (a loop of microns at the leading edge where two halves of a tail
// were sewn). Both its ends are one vertex, so the wires stay closed
// without it; kept, the mesher would put a closed curve's three segments on
// one spot and the faces on either side would fold there. `count` gets the
// edges dropped.
TopoDS_Shape drop_small_loops(const TopoDS_Shape& shape, double tol, const Follow& follow, int& count);

}  // namespace sizemesh::detail
