// Rescue of thin triangles: an inner node next to a triangle under 15
// degrees is moved by a pattern search in uv (rescue_thin_triangles below).
// check_rescue decides where a node goes, apply_move (local_mesh.h) moves it.
#pragma once

#include "mesher/ops/local_mesh.h"

namespace sizemesh {

// Inner nodes next to a triangle under 15 degrees, which smoothing towards
// the neighbours' mean can leave there (a node far off a short boundary
// segment): a pattern search in uv for the position with the fewest
// triangles under 12 degrees around the node, then the largest smallest
// angle. A move is kept when it leaves fewer triangles under 12 degrees, or
// none and a larger smallest angle. Triangles valid before stay valid; one
// that already fails validity (the surface's normal turning over 60 degrees
// within it, where a surface curls within an element) need only stay
// counter-clockwise in uv and not turned against the surface at its centroid.
// Returns the nodes moved.
int rescue_thin_triangles(FaceMesh& fm, const FaceSurface& fs);

namespace ops {

// Where inner node i may move (rescue_thin_triangles): not ok when no
// triangle around it is under 15 degrees, or the search finds no position
// that keeps.
NodeMove check_rescue(const FaceMesh& fm, const FaceSurface& fs, const Balls& balls, int i);

}  // namespace ops
}  // namespace sizemesh
