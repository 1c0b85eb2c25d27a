#include "sizing/size_map.h"

namespace sizemesh {

const char* limit_name(Limit l) {
  switch (l) {
    case Limit::HMax: return "h_max";
    case Limit::Curvature: return "curvature";
    case Limit::FaceProximity: return "face proximity (2A/l)";
    case Limit::CurveLength: return "curve length";
    case Limit::Gap: return "gap through the fluid";
    case Limit::Thickness: return "thickness of the solid";
    case Limit::User: return "user size";
    case Limit::HMin: return "h_min";
    case Limit::FarField: return "far-field size";
    case Limit::Source: return "size source";
    case Limit::Aero: return "wing feature";
  }
  return "?";
}

}  // namespace sizemesh
