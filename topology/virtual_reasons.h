// Why each crossed (virtual) curve was in the mesh's way: what it would have
// forced had the mesh kept it. Measured once the size map exists.
//
// A virtual curve is counted under the first reason that holds:
//  - short: the curve is shorter than the size at its middle (a node at each
//    end closer than one element);
//  - narrow face: a face on either side is narrower (2 area / perimeter, the
//    paper's face width) than that size;
//  - small angle: at an end it meets another curve of a face it bounds at
//    under 12 degrees (a sliver's corner);
//  - smooth: none of these; crossed because nothing sets it apart.
// Work: one size query and a few curve evaluations per curve.
#pragma once

#include <functional>

#include "core/geometry.h"
#include "topology/topology.h"

namespace sizemesh {

struct VirtualReasons {
  int short_curve = 0, narrow_face = 0, small_angle = 0, smooth = 0;
};

// size(face, uv): the element size there (the size map).
VirtualReasons classify_virtual_curves(const Geometry& g, const Topology& t,
                                       const std::function<double(int, const Vec2&)>& size);

}  // namespace sizemesh
