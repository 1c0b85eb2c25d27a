// Mesh improvement of one face after the front closes: edge swaps judged by
// shape in space, smoothing of the nodes inside the face (moved in uv,
// evaluated on the surface), splits of the edges left too long for the size
// map or too far off the surface or turning too much along it (SplitBounds),
// and a last search for nodes next to thin triangles. Validity is kept
// throughout: triangles stay counter-clockwise in uv and facing the surface
// normal in space; boundary nodes and edges are fixed; last, inner nodes too
// close to a neighbour are merged into it (collapse_thin_triangles).
//
// Input/output: fm (triangles and inner node positions change), fs its sampler.
#pragma once

#include "mesher/face_mesh.h"

namespace sizemesh {

// What makes an inner edge too long besides 1.4 sizes (0: no bound).
struct SplitBounds {
  double deviation = 0;  // its middle further than this off the surface
  // The angle (radians) it may turn along the surface, phi_c: over 1.1 sizes
  // long and turning by more than 1.25 max_turn.
  double max_turn = 0;
  // The size map's floor (h_min): no split for turning leaves an edge under
  // it (a radius under h_min / phi_c turns every edge by more than phi_c).
  double h_floor = 0;
};

void optimise(FaceMesh& fm, FaceSurface& fs, int passes, const SplitBounds& bounds = {});

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

// Triangles under 12 degrees whose shortest side ends at an inner node (two
// nodes the front left too close): that node is moved onto the side's other
// end and its two triangles on the side disappear, where every triangle
// around it stays valid, the two ends share no neighbour but the corners
// opposite the side (no triangle doubled) and the smallest angle around it
// grows. The removed nodes are dropped from fm (the others renumbered, loops
// too). Returns the nodes removed.
int collapse_thin_triangles(FaceMesh& fm, const FaceSurface& fs);

}  // namespace sizemesh
