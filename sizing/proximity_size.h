// Proximity sizes per background vertex (paper 3.2.2), plus local gaps.
//
// face:  h_d1 = d_s / mu_d with d_s the face's width across itself, measured
//        from each boundary vertex (the paper's 2 A / l is that width for a
//        strip-shaped face; measured locally it also holds for other shapes)
// curve: h_d0 = length of the shortest curve through the vertex
// (with a deviation bound delta, faces narrower and curves shorter than
// 2 delta are below the accuracy asked for and set no size)
// gap:   g / mu_d, g the distance along the normal (of each face the vertex
//        lies on) to the nearest opposite-facing surface of another face; on
//        the fluid's side (Geometry::fluid_side) the ray crosses the fluid
//        (gaps between parts, slots), on the other the solid (plates, blunt
//        trailing edges); faces closer than `touch` touch and make no gap; a
//        wedge closing at a curve the two faces share is not a gap; beyond
//        the paper.
//
// Inputs:  g geometry, bg background mesh, p (mu_d, local mu_d, local_proximity)
// Outputs: #V sizes each (kNoLimit where the criterion sets no bound).
#pragma once

#include <vector>

#include "background/background_mesh.h"
#include "core/geometry.h"
#include "sizing/params.h"
#include "sizing/size_map.h"

namespace sizemesh {

std::vector<double> face_proximity_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p);
std::vector<double> curve_length_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p);
struct GapSizes {
  explicit GapSizes(int nv) : fluid(nv, kNoLimit), solid(nv, kNoLimit) {}
  std::vector<double> fluid, solid;  // #V each, kNoLimit where none
};
// max_gap: gaps wider than this are not searched (they cannot limit below
// h_max); p.gap_side picks the sides searched (Auto: fluid when the fluid's
// side is known, both otherwise).
GapSizes gap_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p, double max_gap, double touch);

}  // namespace sizemesh
