// The test models (tests/data, see SOURCES.md there) and where to find them.
#pragma once

#include <string>
#include <vector>

namespace sizemesh::test {

struct SharedModel {
  std::string file;
  bool closed;  // a closed solid or sewn closed shell: its meshes must be watertight
};

inline const std::vector<SharedModel>& shared_models() {
  static const std::vector<SharedModel> models = {
      {"onera_m6_wing.stp", true},          {"cone70_capsule_sting.step", true},
      {"hemisphere_cylinder_domain.stp", true}, {"impeller_laufrad.stp", true},
      {"cylinder_head_fins.stp", true},     {"steering_knuckle.stp", true},
      {"d150_fuselage.igs", true},          {"f16_openvsp.stp", false},
      {"manta2_openvsp.stp", false}};
  return models;
}

inline std::string model_path(const std::string& file) { return std::string(SIZEMESH_MODELS_DIR) + "/" + file; }

}  // namespace sizemesh::test
