// The sewn shape's components (its connected pieces) and their description.
#pragma once

#include <TopTools_DataMapOfShapeReal.hxx>
#include <TopoDS_Shape.hxx>

#include <vector>

#include "cad/prepare.h"

namespace sizemesh::detail {

// The connected pieces of the sewn shape: solids, shells outside solids, and
// faces outside shells.
std::vector<TopoDS_Shape> components_of(const TopoDS_Shape& shape);

// What a component is: faces, free curves, closed or not, area and box.
// `area`: exact face areas known from loading (others are computed).
Component describe(const TopoDS_Shape& s, const TopTools_DataMapOfShapeReal& area);

}  // namespace sizemesh::detail
