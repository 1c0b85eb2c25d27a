// Faces lying on each other: within one component (coincident_pairs) and between components (face_to_face).
#pragma once

#include <TopoDS_Shape.hxx>

#include <utility>
#include <vector>

#include "cad/face_list.h"

namespace sizemesh::detail {

// Faces lying on each other: pairs of single faces (same area, centre and
// box within `tol`), then, on one plane, two groups of faces that cover the
// same region (two halves' root caps, each cut in two along its own line).
using FaceGroup = std::vector<int>;
using Coincident = std::vector<std::pair<FaceGroup, FaceGroup>>;
Coincident coincident_pairs(const FaceList& faces, double tol);

// Components that meet face to face: faces of one lie on faces of another
// (a wing's two halves, each closed by its own root cap on the plane
// between them, one of them perhaps left open by the export): a single face
// on a single face (same area, centre and box within `tol`), or on one
// plane the faces of each, cut along different lines, covering the same
// region (areas within a part in a hundred, centres within a hundredth of
// their size). Neither is a wall: the two go through the repair as one
// body, which takes such faces out and sews the halves together. Returns
// pairs (a, b), a < b, each component in one pair at most.
std::vector<std::pair<int, int>> face_to_face(const std::vector<TopoDS_Shape>& parts, double tol);

}  // namespace sizemesh::detail
