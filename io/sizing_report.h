// Summary of the sizing stage: what limited each vertex, what smoothing did, time per step.
#pragma once

#include <ostream>

#include "background/background_mesh.h"
#include "sizing/size_map.h"
#include "sizing/smooth.h"

namespace sizemesh {

void print_sizing_summary(const BackgroundMesh& bg, const SizeMap& m, const SmoothStats& s, std::ostream& out);

}  // namespace sizemesh
