// A point put on several CAD faces at once: a surface, the curve where two
// meet, the point where three do. The mesh-level union puts the nodes of its
// cuts there (they lie on two surfaces), and the cut-face remesher the nodes
// it places along a junction.
#pragma once

#include <vector>

#include "core/geometry.h"

namespace sizemesh {

// The point nearest x on every one of `faces` (a surface, a curve where two
// meet, a point where three do): Newton on the tangent planes, each step the
// smallest move that puts x on all of them. uv holds a start per face and
// ends as the point's uv there. False when a projection fails or the point
// would move further than `reach`.
bool snap(const Geometry& g, const std::vector<int>& faces, std::vector<Vec2>& uv, Vec3& x, double reach,
          double tol);

}  // namespace sizemesh
