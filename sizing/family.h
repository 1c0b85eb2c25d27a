// Mesh families for grid-convergence studies (the drag-prediction workshops'
// coarse, medium and fine grids): one size map scaled by the same factor
// everywhere, so the levels share their topology and the shape of their
// gradation and differ by a uniform refinement (what Richardson
// extrapolation assumes). Level k of n has every size times
// R^((m - k) / 2), m = (n + 1) / 2 (integer division), so its triangle
// count is about R times the previous level's; level m is the map as built.
#pragma once

#include "sizing/params.h"
#include "sizing/size_map.h"

namespace sizemesh {

// The size factor of level k (1 coarsest .. n finest) for the ratio R of triangle counts.
double family_scale(int level, int levels, double ratio);

// The map with every size times s: the smoothed and initial sizes, each
// criterion's, the caps, h_min and h_max (sources and user sizes are in
// them). ln(beta) bounds stay: |grad(s h)| = s |grad h| keeps Eq. 11/12.
SizeMap scaled_map(const SizeMap& m, double s);

// The accuracy rules for sizes times s: the deviation bound times s^2 (a
// chord's sagitta grows with its square), phi_c times s (the turn of an
// element grows with its length), capped below 180 degrees.
SizingParams scaled_rules(const SizingParams& p, double s);

}  // namespace sizemesh
