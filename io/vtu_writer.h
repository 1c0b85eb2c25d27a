// Writes a triangle mesh with named point and cell fields as VTK .vtu (ParaView).
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "core/types.h"

namespace sizemesh {

using Field = std::pair<std::string, std::vector<double>>;

// Throws Error when the file cannot be written.
void write_vtu(const std::string& path, const std::vector<Vec3>& xyz,
               const std::vector<std::array<int, 3>>& tris, const std::vector<Field>& point_data,
               const std::vector<Field>& cell_data);

// Throws Error unless a file can be created at path (checked before long work starts).
void check_writable(const std::string& path);

}  // namespace sizemesh
