// The initial size map (paper 3.2 and 3.4):
//   h_a = min(h_aero, max(h_min, min(h_d, h_c, h_u, h_s, h_max)))
// (h_s: the size sources, sizing/sources.h; h_aero: the chordwise spacing
// asked at leading and trailing edges, which h_min does not floor)
// with every term kept in the SizeMap, plus the ln(beta) bound of every
// background edge (the smallest beta of the faces it touches) and triangle.
//
// Inputs:  g geometry, bg background mesh, p parameters (validated here),
//          diagonal of the model's bounding box (for relative h_min, h_max)
// Output:  SizeMap with h = h_initial.
#pragma once

#include "background/background_mesh.h"
#include "core/geometry.h"
#include "sizing/curvature_size.h"
#include "sizing/params.h"
#include "sizing/size_map.h"

namespace sizemesh {

// memo: optional, the face curvature sizes asked before (sizing/curvature_size.h).
SizeMap initial_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p, double diagonal,
                      CurvatureMemo* memo = nullptr);

}  // namespace sizemesh
