// CGNS output (the standard file of most CFD solvers): one unstructured zone of
// TRI_3 elements in 3D, one element section per marker (io/mesh_labels.h),
// and families that carry the boundary condition a solver should apply.
#pragma once

#include <string>

#include "mesher/surface_mesh.h"
#include "io/mesh_labels.h"

namespace sizemesh {

// Throws Error when the file cannot be written.
void write_cgns(const std::string& path, const SurfaceMesh& m, const MeshLabels& labels);

}  // namespace sizemesh
