// The faces a mesh-level union cut, meshed again by the face mesher: the cut
// leaves each such face a region bounded by its CAD curves and the junction
// polylines, whose segments are as short as the crossings of two unrelated
// meshes made them. Each junction between two corners (nodes where it meets
// a CAD curve or another junction) is sampled again to the size map (Eq. 1a-1b
// along the polyline, as for a CAD curve), each new node put on both
// surfaces; every cut face's region is then meshed from those loops by the
// same front and optimiser as the rest, so the junction carries the quality
// and the sizes of a B-rep union.
//
// Input:  s        the united mesh; u what unite_meshes() reported (its cut edges)
//         g, h, o  the geometry, the size map and the mesher's options
// Output: s with every face the junction touches, or the union's band
//         remesh reached (u.band_faces), meshed again; u's junction,
//         its node count and their distances from the surfaces as they end.
//         A face whose region cannot be walked in uv (corners whose uv
//         disagree, a junction that leaves the parameter domain) or meshed,
//         or whose new triangles open an edge, keeps its triangles, and so
//         do the junctions along it. Where new triangles cross others or
//         turn over (and the old ones there did not), the old triangles
//         around them are held and the rest of the face meshed again around
//         them, the junctions through them keeping their nodes; in the last
//         two rounds such a face keeps all its triangles. The thin
//         triangles left along the junctions are then removed where a local
//         collapse or flip can (junction_slivers.h). s is left as it was
//         when nothing could be done.
// Work:   the cut faces' meshing, and one self-intersection check per round
//         (at most five rounds).
#pragma once

#include "core/geometry.h"
#include "mesher/mesh_union.h"
#include "mesher/surface_mesh.h"
#include "core/size_field.h"

namespace sizemesh {

struct CutFacesResult {
  int faces_remeshed = 0;  // cut faces meshed again from their new boundary
  int faces_kept = 0;      // cut faces left with the union's triangles
  int junction_nodes = 0;  // nodes placed along the junctions
  int thin_collapsed = 0;  // edges collapsed to remove thin triangles along them (junction_slivers.h)
  int thin_flipped = 0;    // edges flipped to the same end
  int thin_pinched = 0;    // nodes put on the face boundary beside them to the same end
};

CutFacesResult remesh_cut_faces(SurfaceMesh& s, const Geometry& g, const SizeField& h, const MeshOptions& o,
                                MeshUnionResult& u);

}  // namespace sizemesh
