// Closes what an advancing front left open (beyond the paper): when the front
// cannot advance from a few edges, the region it still bounds is triangulated
// by ear clipping in uv instead of meshing the whole face again.
//
// Each remaining loop of front edges (uv, unmeshed side on the left) is cut
// into triangles, the best-shaped valid ear first. An ear is valid when it is
// counter-clockwise in uv, holds no other loop node, and does not join two uv
// images of one node in space (a seam). How it must face the surface normal:
//   kFacing    at its corners and at its uv centroid (never an inverted triangle)
//   kCentroid  at its uv centroid only (the quality report's inverted
//              triangle): across a strip narrower than the elements whose
//              surface turns round (a rounded leading edge), no chord faces
//              the normals of both sides
//   kAny       not at all
//
// Inputs:
//   fm          the face's mesh with the front's triangles so far
//   fs          the face's surface sampler
//   open_edges  front edges left open (FrontResult::open_edges)
//   test        how ears must face the surface normal
//   max_edges   larger leftovers are not filled (ears alone make poor triangles)
// Output: true and the new triangles appended to fm.tris when every loop was
// closed; false and fm unchanged otherwise (loops that touch themselves, a
// loop bounding a hole, more than max_edges edges, or no valid ear).
#pragma once

#include <array>
#include <vector>

#include "mesher/face_mesh.h"
#include "mesher/face_surface.h"

namespace sizemesh {

enum class EarTest { kAny, kCentroid, kFacing };

bool fill_front(FaceMesh& fm, const FaceSurface& fs, const std::vector<std::array<int, 2>>& open_edges, EarTest test,
                int max_edges);

}  // namespace sizemesh
