// What each face of the mesh is called in the output files, and the boundary
// condition a solver should give it. Every format carries the same markers:
// the .msh physical groups, the .vtu cell data, the TetGen facet markers, the
// Medit references and the CGNS element sections and families.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "cad/model.h"

namespace sizemesh {

struct MeshLabels {
  struct Marker {
    std::string name;       // "face_12" (a CAD face), "farfield" or "symmetry"
    std::string component;  // the component it belongs to: "component_2", or the name above
    Boundary kind = Boundary::Wall;
  };
  // Marker of mesh face f at [f - 1]: the sewn model's face it came from
  // (1..sewn_faces, the ids of the config file), or one past them for the far
  // field and two past them for the symmetry plane.
  std::vector<int> face_marker;
  std::map<int, Marker> markers;  // every marker a face carries
  // A point inside each body a far field surrounds: the holes a volume
  // mesher leaves empty (TetGen's hole list).
  std::vector<Vec3> holes;
  // Composite face of mesh face f at [f - 1] (topology/); empty: each face its own.
  std::vector<int> face_composite;
  std::string unit;  // the CAD file's length unit ("mm", "ft", ...; "unknown" when it has none)

  int composite_of(int face) const {
    return face >= 1 && face <= static_cast<int>(face_composite.size()) ? face_composite[face - 1] : face;
  }
  int marker_of(int face) const {
    return face >= 1 && face <= static_cast<int>(face_marker.size()) ? face_marker[face - 1] : face;
  }
};

// Markers of the model's faces: their source faces, the components those came
// from (cad/prepare.h), and the far field and symmetry plane.
MeshLabels label_faces(const Model& model);

}  // namespace sizemesh
