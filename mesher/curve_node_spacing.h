// The CAD curve segments beside the junction spaced again before the cut faces are meshed (space_curve_nodes).
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"
#include "core/size_field.h"
#include "mesher/surface_mesh.h"

namespace sizemesh::cut_faces_detail {

// The CAD curve segments that end at a junction corner (where the cut
// crossed a curve), spaced again before the faces are meshed again; only
// segments whose faces are all the corner's (faces the junction cuts) change.
//  - A node closer to the corner than a third of its other segment moves
//    along the curve to midway between its other neighbour and the corner:
//    the cut split a segment near one end, and the stub would be the short
//    side of a sliver in both faces.
//  - A segment longer than 1.5 times the size wanted at its middle is split
//    on the curve to the sizes wanted along it: the curve keeps the spacing
//    of a component's own, coarser size map, while the junction and the
//    region beside it take the finer side's, growing away from it. Not
//    where the junction leaves the corner within 15 degrees of the curve.
//  - Any other curve segment between two faces the junction cuts is split
//    so too where it is longer than 1.5 times the size wanted once the
//    junction's sizes grow into those faces (a strake's junction running
//    beside the fuselage's side curve).
// Triangles at a moved node keep their corners' uv in step; the two beside a
// split segment become fans. True when anything changed.
bool space_curve_nodes(SurfaceMesh& s, const Geometry& g, const SizeField& h,
                       const std::vector<double>& size_slope, const std::vector<std::array<int, 2>>& junction);

}  // namespace sizemesh::cut_faces_detail
