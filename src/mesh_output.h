// Writes the surface mesh, format by the output's extension:
//   .vtu  VTK (ParaView): cell data face_id and min_angle, point data target_size
//   .msh  Gmsh 4.1 ASCII, one surface entity and physical group per face
//   .stl  binary STL
#pragma once

#include <string>
#include <vector>

#include "mesher/surface_mesh.h"

namespace sizemesh {

// Throws Error for an unknown extension (checked before meshing) ...
void check_mesh_format(const std::string& path);
// ... or a file that cannot be written.
void write_mesh(const std::string& path, const SurfaceMesh& m, const std::vector<double>& min_angle,
                const std::vector<double>& target_size);

}  // namespace sizemesh
