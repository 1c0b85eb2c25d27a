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

// Boundary nodes where the surface curls within a sliver far narrower than
// the mesh (a rounded edge of radius well under h at the patch end) take the
// normal 0.75 h inside the face, so the front's and the optimiser's normal
// tests judge triangles by the surface they cover: where the normals 0.75 h
// and 1.05 h inside agree (within 20 degrees) but the boundary's is 45
// degrees or more off. A surface that keeps turning (a fillet or a cone's
// tip narrower than h) is left alone. Returns the number of nodes changed.
int steady_boundary_normals(FaceMesh& fm, const FaceSurface& fs);

// fm's nodes moved out of the bands where the surface does not move across
// (FaceSurface::off_band), their samples taken again there: on a band's edge
// the derivatives vanish across it, the normal is undefined and the front
// cannot place points from it. Positions in the assembled mesh are kept.
FaceMesh off_bands(const FaceMesh& fm, FaceSurface& fs);

}  // namespace sizemesh
