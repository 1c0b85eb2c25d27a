// Background mesh as .vtu: classification (point data) and face ids (cell data).
#pragma once

#include <string>
#include <vector>

#include "geometry/background_mesh.h"
#include "src/vtu_writer.h"

namespace sizemesh {

// `extra_point` / `extra_cell` add fields such as sizes and gradient ratios.
void write_background(const std::string& path, const BackgroundMesh& bg,
                      const std::vector<Field>& extra_point = {}, const std::vector<Field>& extra_cell = {});

}  // namespace sizemesh
