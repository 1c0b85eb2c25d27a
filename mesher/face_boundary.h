// Initial front of a face (paper 4.1): its boundary loops in uv, built from
// the shared curve nodes mapped through the face's pcurves.
//
// Inputs:
//   g   the B-rep; cm the curve discretisation; fs the face's surface sampler
// Output (FaceMesh with nodes and loops, no triangles):
//   one node per curve node use (a seam's nodes appear twice, once per pcurve);
//   a pole (degenerate curve) becomes a uv segment of nodes sharing one global
//   id, split so the first ring of triangles around it has about the wanted size;
//   loops[0] is the outer loop, counter-clockwise in uv, holes clockwise.
// Throws Error when a loop cannot be built (e.g. a missing pcurve).
#pragma once

#include "mesher/discretise_curves.h"
#include "mesher/face_mesh.h"

namespace sizemesh {

FaceMesh face_boundary(const Geometry& g, const CurveMesh& cm, FaceSurface& fs);

}  // namespace sizemesh
