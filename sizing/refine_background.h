// Background refinement for the size map (beyond the paper).
//
// The size map is linear on each background triangle, and a tessellation made
// for geometric accuracy has long edges wherever the surface is flat: a plane
// with small holes, or a long straight trailing edge, is spanned by a few
// triangles whose corners all carry the small sizes of the features at their
// ends. Gradation would let the size grow away from those features, but no
// vertex is there to hold the larger size, so the whole face is meshed at the
// feature's size. This splits every background edge (inside faces and along
// curves) whose graded size at its midpoint, min(h_a, h_b) + ln(beta) l / 2
// capped by h_max, or a quarter of the way from its smaller end (an edge
// reaching h_max can never gain 2x at the middle), exceeds the linear
// interpolation there by more than
// the factor kRefineGain (where the curvature at the midpoint allows it), and every
// edge whose midpoint curvature size, or triangle (its longest edge) whose
// curvature size at its centroid or halfway to a corner, is below the linear
// one by the factor kCurvatureMiss (a curvature peak the tessellation stepped
// over; the deviation of an element grows with the square of its size, so a
// smaller factor), recomputing the initial and
// edge-graded sizes after each round, until no edge qualifies or kRefineMaxRounds
// rounds have run. Before the first round and after each one, edges inside
// faces are flipped to make the background Delaunay in space.
//
// Inputs:  g geometry, bg background mesh (refined in place), p parameters, diagonal,
//          and the initial size map on bg
// Output:  the initial size map on the refined background (not yet smoothed).
#pragma once

#include "background/background_mesh.h"
#include "core/geometry.h"
#include "sizing/params.h"
#include "sizing/size_map.h"

namespace sizemesh {

struct RefineStats {
  int rounds = 0;
  int edges_split = 0;
  int flips = 0;  // Delaunay flips, before and after each round of splits
  int vertices_before = 0, vertices_after = 0;
};

// The factor by which the graded midpoint size must exceed the linear one.
constexpr double kRefineGain = 2.0;
constexpr double kCurvatureMiss = 1.25;
constexpr int kRefineMaxRounds = 8;

// m: the initial size map on bg (initial_sizes()), replaced by the one on the
// refined background. The edges are flipped to Delaunay in space before and
// after each round of splits; `flips` false leaves them (only to measure
// what the flips give).
void refine_background(const Geometry& g, BackgroundMesh& bg, const SizingParams& p, double diagonal, SizeMap& m,
                       RefineStats* stats = nullptr, bool flips = true);
// Both steps: the initial sizes, then the refinement.
SizeMap refine_background(const Geometry& g, BackgroundMesh& bg, const SizingParams& p, double diagonal,
                          RefineStats* stats = nullptr, bool flips = true);

}  // namespace sizemesh
