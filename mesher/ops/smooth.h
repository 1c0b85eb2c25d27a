// Smoothing: an inner node moves towards the mean of its neighbours in space
// (one Gauss-Newton step in uv, evaluated on the surface), kept only if the
// worst shape around it does not get worse.
//
// Inputs: fm, fs and the triangles around each node (Balls, local_mesh.h).
// Output: the node's new uv and surface sample (apply_move()).
#pragma once

#include "mesher/ops/local_mesh.h"

namespace sizemesh::ops {

// Where inner node i may move: the full step towards its neighbours' mean,
// else half of it, the first that the surface can evaluate and that leaves
// every triangle around i valid and none worse in shape than the worst
// before. Not ok when neither does, or the step cannot be computed.
NodeMove check_smooth(const FaceMesh& fm, const FaceSurface& fs, const Balls& balls, int i);

// One sweep of smoothing over the inner nodes in order, each move applied
// before the next node is checked. Returns the nodes moved.
int smooth_sweep(FaceMesh& fm, const FaceSurface& fs);

}  // namespace sizemesh::ops
