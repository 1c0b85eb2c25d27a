#include "io/mesh_labels.h"

namespace sizemesh {

MeshLabels label_faces(const Model& model) {
  MeshLabels labels;
  const int sewn = model.info().sewn_faces;
  std::vector<int> component(sewn + 1, 0);  // sewn face -> component (1-based), 0: none
  const auto& components = model.info().preparation.components;
  for (size_t k = 0; k < components.size(); ++k)
    for (int f : components[k].face_ids)
      if (f >= 1 && f <= sewn) component[f] = static_cast<int>(k) + 1;
  labels.face_marker.resize(model.num_faces());
  for (int f = 1; f <= model.num_faces(); ++f) {
    const Boundary kind = model.boundary(f);
    int marker = model.source_face(f);
    MeshLabels::Marker m;
    m.kind = kind;
    if (kind == Boundary::Farfield || kind == Boundary::Symmetry) {
      marker = sewn + (kind == Boundary::Farfield ? 1 : 2);
      m.name = m.component = kind == Boundary::Farfield ? "farfield" : "symmetry";
    } else {
      if (marker < 1 || marker > sewn) marker = f;  // made by the preparation with no known source
      m.name = "face_" + std::to_string(marker);
      const int c = marker <= sewn ? component[marker] : 0;
      m.component = c > 0 ? "component_" + std::to_string(c) : "body";
    }
    labels.face_marker[f - 1] = marker;
    labels.markers.emplace(marker, m);
  }
  labels.holes = model.info().domain.inside_points;
  labels.unit = model.info().unit;
  return labels;
}

}  // namespace sizemesh
