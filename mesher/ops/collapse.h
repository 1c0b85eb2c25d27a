// Collapse of thin triangles: the inner end of a thin triangle's shortest
// side is merged into the other end (two nodes the front left too close).
// check_collapse decides which end goes, apply_collapse moves it and marks
// what dies; collapse_thin_triangles sweeps and then drops the dead.
#pragma once

#include <vector>

#include "mesher/ops/local_mesh.h"

namespace sizemesh {

// Triangles under 12 degrees whose shortest side ends at an inner node (two
// nodes the front left too close): that node is moved onto the side's other
// end and its two triangles on the side disappear, where every triangle
// around it stays valid, the two ends share no neighbour but the corners
// opposite the side (no triangle doubled) and the smallest angle around it
// grows. The removed nodes are dropped from fm (the others renumbered, loops
// too). Returns the nodes removed.
int collapse_thin_triangles(FaceMesh& fm, const FaceSurface& fs);

namespace ops {

// Which end of thin triangle t's shortest side may be removed onto the
// other: r (-1: none) goes onto keep. Neither end may be locked (next to a
// collapse already made); of the inner ends whose removal keeps every
// triangle of its ball valid, meets the link condition and raises the
// ball's smallest angle, the one that raises it most.
struct CollapseCheck {
  int r = -1, keep = -1;
  bool ok() const { return r >= 0; }
};
CollapseCheck check_collapse(const FaceMesh& fm, const FaceSurface& fs, const Balls& balls,
                             const std::vector<char>& locked, int t);

// The collapse check_collapse allowed: r's triangles on the side are marked
// dead, its others get keep in its place; r is marked removed, and r, keep
// and their neighbours locked. fm keeps its nodes and triangles (the sweep
// drops the dead and removed ones at its end).
void apply_collapse(FaceMesh& fm, const Balls& balls, const CollapseCheck& c, std::vector<char>& dead,
                    std::vector<char>& locked, std::vector<char>& removed);

}  // namespace ops
}  // namespace sizemesh
