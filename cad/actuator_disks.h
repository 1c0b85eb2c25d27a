// Flat disks a body passes through (a propeller's actuator disk): open components that are no wall.
#pragma once

#include <TopoDS_Shape.hxx>
#include <gp_Pln.hxx>

#include <vector>

namespace sizemesh::detail {

// An open component whose faces all lie on one plane (`plane` gets it) and
// whose outer rim is a circle: the free curves' points beyond half the
// largest distance from the centroid all lie within 5% of it (an annulus's
// inner rim is not the rim). A propeller's or rotor's disk.
bool flat_disk(const TopoDS_Shape& s, double tol, gp_Pln& plane);

// A flat disk on `plane` that one of the `solids` passes through: the
// solid's section by the plane lies within the disk (a propeller's
// actuator disk around its nacelle or spinner). It has fluid on both sides
// and bounds no volume, so it is no wall of the wetted surface; imprinted
// on the body it would leave boundary and non-manifold edges. A flat sheet
// a body only touches or ends in (a plate fin on a fuselage) is a wall.
bool pierced(const TopoDS_Shape& sheet, const gp_Pln& plane, const std::vector<TopoDS_Shape>& solids, double tol);

}  // namespace sizemesh::detail
