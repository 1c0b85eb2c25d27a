// Closing the slot between two components that lie on each other, before their union.
//
// Internal to the mesh-level union (mesher/mesh_union.cpp).
#pragma once

#include <set>
#include <vector>

#include "mesher/tracked_mesh.h"

namespace sizemesh::mesh_union_detail {

// Closes the slots between `part` and `base` (see GapSide in close_gaps.cpp);
// the source nodes moved go to `moved`.
void close_gaps(Tracked& part, Tracked& base, const std::vector<double>& node_h, std::set<int>& moved);

}  // namespace sizemesh::mesh_union_detail
