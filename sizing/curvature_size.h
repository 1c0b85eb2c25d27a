// Curvature size per background vertex (paper 3.2.1): h_c = 2 r sin(phi_c / 2)
// with r = 1 / k, k the largest absolute principal curvature over every face
// the vertex lies on (at its uv there), and for vertices on curves also the
// curve's own curvature. Local phi_c per face and per curve apply where set.
//
// Inputs:  g geometry, bg background mesh, p parameters (phi_c, local phi_c)
// Output:  #V sizes, kNoLimit where the surface is flat or the curvature is
//          undefined (poles, apexes, evaluation failures): never 0 or NaN.
#pragma once

#include <vector>

#include "geometry/background_mesh.h"
#include "geometry/geometry.h"
#include "sizing/params.h"
#include "sizing/size_map.h"

namespace sizemesh {

std::vector<double> curvature_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p);

// 2 r sin(phi/2) for curvature k (1/length) and phi in degrees; kNoLimit for k <= 0.
double chord_size(double k, double phi_deg);

}  // namespace sizemesh
