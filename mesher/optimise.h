// Mesh improvement of one face after the front closes: edge swaps judged by
// shape in space, smoothing of the nodes inside the face (moved in uv,
// evaluated on the surface), splits of the edges left too long for the size
// map or too far off the surface or turning too much along it (SplitBounds),
// and a last search for nodes next to thin triangles. Validity is kept
// throughout: triangles stay counter-clockwise in uv and facing the surface
// normal in space; boundary nodes and edges are fixed; last, inner nodes too
// close to a neighbour are merged into it (collapse_thin_triangles).
//
// Each local operation is one file of mesher/ops/ (swap, smooth, split,
// rescue, collapse), its check apart from its apply; optimise() runs them.
//
// Input/output: fm (triangles and inner node positions change), fs its sampler.
#pragma once

#include "mesher/face_mesh.h"
#include "mesher/ops/collapse.h"  // collapse_thin_triangles
#include "mesher/ops/rescue.h"    // rescue_thin_triangles
#include "mesher/ops/split.h"     // SplitBounds

namespace sizemesh {

void optimise(FaceMesh& fm, FaceSurface& fs, int passes, const SplitBounds& bounds = {});

}  // namespace sizemesh
