// Prescribed sizes h_u (paper 3.4): a number or an expression of x, y, z per
// point, curve or face, applied to the background vertices lying on it (a
// curve's includes its end points, a face's includes its boundary).
//
// Inputs:  g geometry, bg background mesh, p (point_size, curve_size, face_size)
// Output:  #V sizes, kNoLimit where nothing is prescribed; the smallest wins.
// Throws Error for a malformed expression or one that is not positive.
#pragma once

#include <vector>

#include "background/background_mesh.h"
#include "core/geometry.h"
#include "sizing/params.h"

namespace sizemesh {

std::vector<double> user_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p);

}  // namespace sizemesh
