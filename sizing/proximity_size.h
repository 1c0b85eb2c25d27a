// Proximity sizes per background vertex (paper 3.2.2), plus local gaps.
//
// face:  h_d1 = d_s / mu_d with d_s the face's width across itself, measured
//        from each boundary vertex (the paper's 2 A / l is that width for a
//        strip-shaped face; measured locally it also holds for other shapes)
// curve: h_d0 = length of the shortest curve through the vertex
// gap:   g / mu_d, g the distance along +-normal (of each face the vertex lies
//        on) to the nearest opposite-facing surface of another face (thin
//        plates, blunt trailing edges, gaps between parts); a wedge closing at
//        a curve the two faces share is not a gap; beyond the paper.
//
// Inputs:  g geometry, bg background mesh, p (mu_d, local mu_d, local_proximity)
// Outputs: #V sizes each (kNoLimit where the criterion sets no bound).
#pragma once

#include <vector>

#include "geometry/background_mesh.h"
#include "geometry/geometry.h"
#include "sizing/params.h"

namespace sizemesh {

std::vector<double> face_proximity_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p);
std::vector<double> curve_length_sizes(const Geometry& g, const BackgroundMesh& bg);
// max_gap: gaps wider than this are not searched (they cannot limit below h_max).
std::vector<double> gap_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p, double max_gap);

}  // namespace sizemesh
