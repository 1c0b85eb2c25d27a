#include "app/info.h"

#include <iomanip>

namespace sizemesh {

void print_info(const Model& model, std::ostream& out) {
  const ModelInfo& i = model.info();
  out << "file:        " << i.path << " (" << i.format << ")\n"
      << "unit:        " << i.unit << "\n"
      << std::setprecision(6) << "bounding box: [" << i.bbox_min.x() << ", " << i.bbox_min.y() << ", "
      << i.bbox_min.z() << "] - [" << i.bbox_max.x() << ", " << i.bbox_max.y() << ", " << i.bbox_max.z()
      << "], diagonal " << i.diagonal() << "\n"
      << "solids:      " << i.solids << "\n"
      << "shells:      " << i.shells << "\n"
      << "faces:       " << i.faces;
  if (i.faces != i.faces_before_sewing) out << " (" << i.faces_before_sewing << " before sewing)";
  if (i.zero_area_faces_removed) out << ", " << i.zero_area_faces_removed << " faces of zero area removed";
  out << "\n"
      << "curves:      " << i.curves << "\n"
      << "points:      " << i.points << "\n"
      << "free curves: " << i.free_curves_before_sewing << " before sewing, " << i.free_curves_after_sewing
      << " after" << (i.sewn ? "" : " (not sewn)") << "\n";
  const Preparation& prep = i.preparation;
  out << "components:  " << prep.components.size() << " after sewing\n";
  int k = 0;
  for (const Component& c : prep.components) {
    out << std::setprecision(4) << "  " << ++k << ": " << c.faces << " faces, "
        << (c.closed ? "closed" : std::to_string(c.free_curves) + " free curves") << ", area " << c.area << ", box ["
        << c.bbox_min.x() << ", " << c.bbox_min.y() << ", " << c.bbox_min.z() << "] - [" << c.bbox_max.x() << ", "
        << c.bbox_max.y() << ", " << c.bbox_max.z() << "] -> " << c.role;
    if (!c.route.empty()) out << ", " << c.route;
    if (c.faces_removed) out << " (" << c.faces_removed << " faces taken out)";
    if (c.caps_added) out << " (" << c.caps_added << " planar caps added)";
    out << "\n";
  }
  if (prep.union_requested) {
    out << "union:       ";
    if (prep.union_skipped) out << "not run: --info describes the file, a mesh run unites its components";
    else if (prep.fused) out << prep.solids_fused << " solids fused";
    if (!prep.not_united.empty()) out << (prep.fused ? ", " : "") << prep.not_united.size() << " components not united";
    if (!prep.union_skipped && !prep.fused && prep.not_united.empty()) out << (prep.fallback.empty() ? "not needed" : "not kept: " + prep.fallback);
    out << "; " << prep.duplicate_faces_removed << " duplicate and " << prep.internal_faces_removed
        << " internal faces removed; " << prep.faces_split_at_folds << " split at folds or parameter jumps; "
        << prep.faces_made_planar << " flat faces put on their plane; "
        << prep.faces_before << " faces before, " << prep.faces_after << " after\n";
  }
  const FlowDomain& d = i.domain;
  if (!d.farfield.empty())
    out << std::setprecision(6) << "far field:   " << d.farfield << " of size " << d.size << " around [" << d.center.x()
        << ", " << d.center.y() << ", " << d.center.z() << "], elements " << d.element_size << ", "
        << d.farfield_faces << " faces; " << d.inside_points.size() << " bodies inside\n";
  if (d.symmetry_axis >= 0)
    out << std::setprecision(6) << "symmetry:    " << static_cast<char>('x' + d.symmetry_axis) << " = " << d.symmetry_at
        << ", " << d.symmetry_faces << " faces\n";
  if (i.preparation.half_model_axis >= 0)
    out << "half model:  open on the plane " << static_cast<char>('x' + i.preparation.half_model_axis)
        << " = 0 (--symmetry " << static_cast<char>('x' + i.preparation.half_model_axis)
        << " with a far field closes it)\n";
  for (const auto& line : i.read_repairs) out << "repaired:    " << line << "\n";
  if (i.entities_failed)
    out << "unread:      " << i.entities_failed << " entities; first: " << i.first_failure << "\n";
  int named = 0;
  for (int f = 1; f <= i.faces; ++f)
    if (!model.face_name(f).empty()) out << (named++ ? ", " : "named faces: ") << f << " '" << model.face_name(f) << "'";
  if (named) out << "\n";
}

}  // namespace sizemesh
