// Background mesh as .vtu: classification (point data) and face ids (cell data).
#pragma once

#include <string>
#include <vector>

#include "background/background_mesh.h"
#include "sizing/size_map.h"
#include "topology/wing_features.h"
#include "io/vtu_writer.h"

namespace sizemesh {

// `extra_point` / `extra_cell` add fields such as sizes and gradient ratios.
void write_background(const std::string& path, const BackgroundMesh& bg,
                      const std::vector<Field>& extra_point = {}, const std::vector<Field>& extra_cell = {});

// The background mesh with every size criterion (point data h_curvature,
// h_proximity, h_user, h_source, h_aero, h_initial, h_smoothed; "no limit"
// written as h_max), limited_by, and the cell data gradient_ratio =
// |grad h| / ln(beta). With `wing`, point data wing_feature: 1 on a leading
// edge's curve, 2 on a trailing edge's, 0 elsewhere.
void write_background_sizes(const std::string& path, const BackgroundMesh& bg, const SizeMap& m,
                            const WingFeatures* wing = nullptr);

}  // namespace sizemesh
