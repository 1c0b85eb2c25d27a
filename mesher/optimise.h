// Mesh improvement of one face after the front closes: edge swaps judged by
// shape in space, and smoothing of the nodes inside the face (moved in uv,
// evaluated on the surface). Validity is kept throughout: triangles stay
// counter-clockwise in uv and facing the surface normal in space; boundary
// nodes and edges are fixed.
//
// Input/output: fm (triangles and inner node positions change), fs its sampler.
#pragma once

#include "mesher/face_mesh.h"

namespace sizemesh {

void optimise(FaceMesh& fm, FaceSurface& fs, int passes);

}  // namespace sizemesh
