// Human-readable summary of a loaded model (`sizemesh --info`).
#pragma once

#include <ostream>

#include "cad/model.h"

namespace sizemesh {

void print_info(const Model& model, std::ostream& out);

}  // namespace sizemesh
