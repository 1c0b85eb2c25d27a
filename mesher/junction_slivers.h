// Thin triangles left along a union of meshes' junction, removed by local
// operations on the final mesh. Where the junction runs within a sliver's
// width of a CAD curve (a wing's leading edge lying along a fuselage's flat
// top) or crosses one at a grazing angle, the cut faces hold strips narrower
// than the elements, and no front fills them without thin triangles. Each
// such triangle is replaced by the local operation that leaves its
// neighbourhood best:
//  - an edge collapsed: a node merged into a neighbour on every face it is
//    on (an inner node into any neighbour, a curve's or junction's node into
//    the next one along it or into a corner there), or two nodes of different
//    curves or junctions closer than tan(12 deg) of the wanted size merged
//    (the strip between them vanishes: a corner of three faces there);
//  - the edge opposite its largest angle flipped, inside one face, or where
//    that edge is a face boundary, the node at that angle put on it (the
//    triangle across it split there: a junction that touches a curve
//    meets it).
// An operation is taken only when its triangles have fewer under 12 degrees
// than the ones it replaces (their smallest angle not under a quarter of
// theirs: a strip goes in several steps), or as many and a larger smallest
// angle; none turned over or leaning more than 45 degrees off its surface
// (the normal at its centroid), none a thin ear of its face's boundary at a
// corner that is not its smallest angle. B-rep points never move.
//
// Input:  s the mesh after the cut faces were meshed again, junction its
//         junction edges, crossing_pairs its count of crossing triangle pairs
// Output: s with its thin junction triangles removed where that was possible,
//         junction renumbered with it; s is left as it was when the result
//         would have more crossing pairs.
// Work:   a few operations per thin triangle, each over its star; one
//         self-intersection count when anything changed.
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"
#include "mesher/surface_mesh.h"
#include "core/size_field.h"

namespace sizemesh {

struct JunctionSliverResult {
  int collapsed = 0;  // edges collapsed
  int flipped = 0;    // edges flipped
  int pinched = 0;    // nodes put on a face boundary their thin triangle lay along
};

JunctionSliverResult remove_junction_slivers(SurfaceMesh& s, const Geometry& g, const SizeField& h,
                                             std::vector<std::array<int, 2>>& junction, long long crossing_pairs);

}  // namespace sizemesh
