// Thin triangles the shape forces: those whose smallest angle sits at a
// corner where two kept edges (feature curves, junctions, free boundaries;
// mesher/composite_remesh.h kept_edges) meet at under 12 degrees, the wedge
// between them measured as the sum of the triangles' angles at the corner.
// Every other triangle under 12 degrees could be avoided by some mesh of the
// same surface: the measure of slivers.
//
// Input:  m the mesh, kept its kept edges (edge_key), min_angle per triangle.
// Output: per triangle 1 when it is under 12 degrees at such a corner, else 0.
// Work:   one walk round the corner of each thin triangle.
#pragma once

#include <cstdint>
#include <unordered_set>
#include <vector>

#include "mesher/surface_mesh.h"

namespace sizemesh {

std::vector<char> at_feature_corners(const SurfaceMesh& m, const std::unordered_set<uint64_t>& kept,
                                     const std::vector<double>& min_angle);

}  // namespace sizemesh
