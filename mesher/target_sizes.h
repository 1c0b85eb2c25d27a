// The size map's target size at every node of a mesh (written with the mesh so
// a viewer can compare edge lengths with the map), looked up in the uv the node
// has in the first triangle that uses it, with walk hints kept per face.
#pragma once

#include <vector>

#include "mesher/surface_mesh.h"
#include "core/size_field.h"

namespace sizemesh {

// #nodes sizes; -1 for a node no triangle uses.
std::vector<double> target_sizes(const SurfaceMesh& mesh, const SizeField& h);

}  // namespace sizemesh
