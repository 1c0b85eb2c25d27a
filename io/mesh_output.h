// Writes the surface mesh, format by the output's extension:
//   .vtu  VTK (ParaView): cell data face_id, source_face_id, min_angle and
//         sliver (0 not under 12 degrees, 1 forced by the CAD, 2 avoidable),
//         point data target_size and classification
//   .msh  Gmsh 4.1 ASCII, one surface entity per face, in the physical group
//         of its source face ("face_<id>": the sewn model's face it came from)
//   .stl  binary STL
//   .cgns CGNS (io/cgns_writer.h)
//   .mesh Medit (Mmg): triangles referenced by marker
//   .smesh TetGen: facets with boundary markers, and holes inside the bodies a far field surrounds
#pragma once

#include <string>
#include <vector>

#include "mesher/quality.h"
#include "mesher/surface_mesh.h"
#include "io/mesh_labels.h"

namespace sizemesh {

// Throws Error for an unknown extension (checked before meshing) ...
void check_mesh_format(const std::string& path);
// ... or a file that cannot be written.
// labels: each face's marker, name and boundary kind (io/mesh_labels.h).
// q: the mesh's quality (per-triangle smallest angle and sliver kind).
// target_size, limited_by: per node, the size map's size and the rule behind
// it (.vtu point data; limited_by may be empty).
void write_mesh(const std::string& path, const SurfaceMesh& m, const MeshLabels& labels, const MeshQuality& q,
                const std::vector<double>& target_size, const std::vector<double>& limited_by = {});

}  // namespace sizemesh
