#include "io/report.h"

#include <fstream>
#include <iomanip>

namespace sizemesh {

nlohmann::json report_json(const RunReport& r) {
  using nlohmann::json;
  const ModelInfo& info = r.model->info();
  json j;
  double cad_area = 0;
  for (int f = 1; f <= r.model->num_faces(); ++f) cad_area += r.model->face_area(f);
  j["model"] = {{"cad_area", cad_area},
                {"closed", r.model->closed()},
                {"diagonal", info.diagonal()},
                {"file", info.path},       {"format", info.format},   {"unit", info.unit},
                {"faces", info.faces},     {"curves", info.curves},   {"points", info.points},
                {"solids", info.solids},   {"free_curves_after_sewing", info.free_curves_after_sewing},
                {"entities_failed", info.entities_failed}, {"first_failed_entity", info.first_failure}};
  const Preparation& prep = info.preparation;
  json components = json::array();
  for (const Component& c : prep.components)
    components.push_back({{"faces", c.faces},
                          {"closed", c.closed},
                          {"free_curves", c.free_curves},
                          {"area", c.area},
                          {"bbox_min", {c.bbox_min.x(), c.bbox_min.y(), c.bbox_min.z()}},
                          {"bbox_max", {c.bbox_max.x(), c.bbox_max.y(), c.bbox_max.z()}},
                          {"role", c.role},
                          {"route", c.route},
                          {"brep_failure", c.brep_failure},
                          {"caps_added", c.caps_added},
                          {"faces_removed", c.faces_removed}});
  if (r.topology && !r.topology->curve_kind.empty()) {
    const Topology& t = *r.topology;
    json kinds = json::object();
    for (CurveKind k : {CurveKind::Virtual, CurveKind::Seam, CurveKind::Angle, CurveKind::Marker, CurveKind::User,
                        CurveKind::Boundary, CurveKind::Degenerate})
      kinds[curve_kind_name(k)] = t.count(k);
    j["topology"] = {{"enabled", t.enabled},
                     {"feature_angle_deg", t.feature_angle_deg},
                     {"composite_faces", t.composites},
                     {"composite_curves", t.composite_curves},
                     {"curves_by_kind", kinds},
                     {"virtual_by_reason", {{"short", r.virtual_reasons.short_curve},
                                            {"narrow_face", r.virtual_reasons.narrow_face},
                                            {"small_angle", r.virtual_reasons.small_angle},
                                            {"smooth", r.virtual_reasons.smooth}}}};
  }
  if (r.wing) {
    nlohmann::json bases = nlohmann::json::array();
    for (const WingFeatures::Base& b : r.wing->bases)
      bases.push_back({{"faces", b.faces}, {"width_min", b.width_min}, {"width_max", b.width_max}});
    nlohmann::json tips = nlohmann::json::array();
    for (const WingFeatures::Tip& t : r.wing->tips) tips.push_back({{"faces", t.faces}, {"chord", t.chord}});
    j["wing"] = {{"leading_edges", r.wing->leading},
                 {"trailing_edges", r.wing->trailing},
                 {"leading_length", r.wing->leading_length},
                 {"trailing_length", r.wing->trailing_length},
                 {"chord_min", r.wing->chord_min},
                 {"chord_max", r.wing->chord_max},
                 {"blunt_bases", bases},
                 {"tips", tips}};
  }
  j["preparation"] = {{"components", components},
                      {"union_requested", prep.union_requested},
                      {"fused", prep.fused},
                      {"solids_fused", prep.solids_fused},
                      {"fallback", prep.fallback},
                      {"not_united", prep.not_united},
                      {"left_out", prep.left_out},
                      {"internal_sheets", prep.internal_sheets},
                      {"united_at_mesh_level", prep.united_at_mesh_level},
                      {"caps_added", prep.caps_added},
                      {"half_model_axis", prep.half_model_axis},
                      {"union_seconds", prep.seconds_budget},
                      {"duplicate_faces_removed", prep.duplicate_faces_removed},
                      {"internal_faces_removed", prep.internal_faces_removed},
                      {"pocket_faces_removed", prep.pocket_faces_removed},
                      {"components_repaired", prep.components_repaired},
                      {"faces_split_at_folds", prep.faces_split_at_folds},
                      {"faces_made_planar", prep.faces_made_planar},
                      {"strip_faces_collapsed", prep.strip_faces_collapsed},
                      {"small_loops_dropped", prep.small_loops_dropped},
                      {"edges_made_real", prep.edges_made_real},
                      {"faces_before", prep.faces_before},
                      {"faces_after", prep.faces_after},
                      {"seconds",
                       {{"repair", prep.repair_seconds},
                        {"union", prep.union_seconds},
                        {"imprint", prep.imprint_seconds},
                        {"finish", prep.finish_seconds}}}};
  const FlowDomain& d = info.domain;
  j["domain"] = {{"farfield", d.farfield},
                 {"farfield_size", d.size},
                 {"farfield_element_size", d.element_size},
                 {"center", {d.center.x(), d.center.y(), d.center.z()}},
                 {"farfield_faces", d.farfield_faces},
                 {"symmetry_axis", d.symmetry_axis < 0 ? std::string() : std::string(1, 'x' + d.symmetry_axis)},
                 {"symmetry_at", d.symmetry_at},
                 {"symmetry_faces", d.symmetry_faces},
                 {"bodies_inside", d.inside_points.size()}};
  j["background"] = {{"triangles", r.background_triangles},
                     {"vertices", r.background_vertices},
                     {"tessellation_vertices", r.refinement.vertices_before},
                     {"refinement_rounds", r.refinement.rounds},
                     {"refinement_edges_split", r.refinement.edges_split},
                     {"refinement_flips", r.refinement.flips}};
  if (r.sizes) {
    std::vector<int> count(kNumLimits, 0);
    for (Limit l : r.sizes->limit) ++count[static_cast<int>(l)];
    json limited;
    for (int i = 0; i < kNumLimits; ++i) limited[limit_name(static_cast<Limit>(i))] = count[i];
    j["sizing"] = {{"h_min", r.sizes->h_min},
                   {"h_max", r.sizes->h_max},
                   {"vertices_limited_by", limited},
                   {"smoothing_lowered", r.smoothing.lowered},
                   {"smoothing_max_reduction", r.smoothing.max_reduction},
                   {"smoothing_rounds", r.smoothing.rounds},
                   {"smoothing_steep_triangles", r.smoothing.steep_triangles}};
  }
  if (r.mesh) {
    const MeshQuality& q = r.quality;
    const double n = std::max(1, q.triangles);
    json failures = json::array();
    for (const auto& f : r.mesh->failures) failures.push_back({{"face", f.face}, {"reason", f.reason}});
    std::vector<int> hist(q.histogram.begin(), q.histogram.end());
    j["mesh"] = {{"triangles", q.triangles},
                 {"nodes", q.nodes},
                 {"min_angle_histogram_6deg", hist},
                 {"worst_min_angle_deg", q.worst_angle},
                 {"bad_below_12deg", q.below_12},
                 {"bad_share", q.below_12 / n},
                 {"forced_below_12deg", q.forced_below_12},
                 {"narrow_face_below_12deg", q.narrow_below_12},
                 {"short_curve_below_12deg", q.short_curve_below_12},
                 {"avoidable_below_12deg", q.avoidable_below_12},
                 {"below_12deg_at_feature_corners", q.feature_corner_below_12},
                 {"below_12deg_elsewhere", q.below_12 - q.feature_corner_below_12},
                 {"low_quality_below_24deg", q.below_24},
                 {"low_quality_share", q.below_24 / n},
                 {"size_conformity", q.size_conformity},
                 {"share_at_h_min", r.at_h_min_share},
                 {"area_share_at_h_min", r.at_h_min_area_share},
                 {"boundary_edges", q.boundary_edges},
                 {"nonmanifold_edges", q.nonmanifold_edges},
                 {"open_faces", q.open_faces},
                 {"inverted_faces", q.inverted_faces},
                 {"orientation_conflicts", q.orientation_conflicts},
                 {"inverted_triangles", q.inverted},
                 {"zero_area_triangles", q.zero_area},
                 {"self_intersecting_pairs", q.self_intersections},
                 {"local_self_intersecting_pairs", q.local_self_intersections},
                 {"locally_intersecting_faces", q.intersecting_faces},
                 {"crossing_faces", q.crossing_faces},
                 {"area", q.area},
                 {"max_inner_node_distance", q.max_inner_node_distance},
                 {"max_node_distance", q.max_node_distance},
                 {"failed_faces", failures}};
    const MeshStats& st = r.mesh->stats;
    j["mesher"] = {{"estimated_triangles", r.estimated_triangles},
                   {"front_steps", st.front_steps},
                   {"front_steps_per_triangle", st.front_steps / n},
                   {"front_work_per_step", st.front_work / std::max(1.0, double(st.front_steps))},
                   {"faces_retried", st.faces_retried},
                   {"faces_relaxed", st.faces_relaxed},
                   {"faces_lenient", st.faces_lenient},
                   {"faces_filled", st.faces_filled},
                   {"back_to_back_dropped", st.back_to_back_dropped},
                   {"shared_edges_flipped", st.shared_edges_flipped}};
    for (const auto& [stage, e] : r.evaluations)
      if (stage == "meshing") j["mesher"]["surface_evaluations_per_triangle"] = e / n;
    j["mesher"]["surface_evaluations"] = {{"face_setup", st.evaluations_setup},
                                          {"front", st.evaluations_front},
                                          {"optimise", st.evaluations_optimise}};
    j["mesh_union"] = {{"united", r.mesh_union.united},
                       {"failed", std::count_if(r.mesh_union.failures.begin(), r.mesh_union.failures.end(),
                                                [](const std::string& f) { return !f.empty(); })},
                       {"rest_pieces_apart", r.mesh_union.rest_pieces_apart},
                       {"gap_nodes_closed", r.mesh_union.gap_nodes_closed},
                       {"junction_nodes", r.mesh_union.junction_nodes},
                       {"junction_nodes_off_surface", r.mesh_union.junction_nodes_off},
                       {"band_triangles", r.mesh_union.band_triangles},
                       {"band_classes_undone", r.mesh_union.band_classes_undone},
                       {"max_junction_gap", r.mesh_union.max_junction_gap},
                       {"junction_nodes_unprojected", r.mesh_union.junction_nodes_unprojected},
                       {"faces_remeshed", r.cut_faces.faces_remeshed},
                       {"faces_kept", r.cut_faces.faces_kept},
                       {"junction_nodes_placed", r.cut_faces.junction_nodes},
                       {"thin_edges_collapsed", r.cut_faces.thin_collapsed},
                       {"thin_edges_flipped", r.cut_faces.thin_flipped},
                       {"thin_nodes_pinched", r.cut_faces.thin_pinched}};
    j["composite"] = {{"virtual_curve_nodes", r.composite.virtual_nodes},
                      {"virtual_curve_nodes_left", r.composite.virtual_nodes_left},
                      {"edges_collapsed", r.composite.collapsed},
                      {"edges_split", r.composite.split},
                      {"edges_flipped", r.composite.flipped},
                      {"nodes_smoothed", r.composite.smoothed},
                      {"nodes_slid_along_curves", r.composite.slid},
                      {"attempts_undone_crossing", r.composite.attempts_crossing}};
    j["size_query"] = {{"queries", r.queries.queries},
                       {"mean_triangles_visited", r.queries.mean_visited()},
                       {"max_triangles_visited", r.queries.max_visited},
                       {"fallbacks", r.queries.fallbacks},
                       {"outside_domain", r.queries.outside}};
  }
  json t;
  for (const auto& [stage, s] : r.seconds) t[stage] = s;
  j["seconds"] = t;
  json e = json::object();
  for (const auto& [stage, count] : r.evaluations) e[stage] = count;
  j["surface_evaluations"] = e;
  return j;
}

void print_mesh_summary(const RunReport& r, std::ostream& out) {
  if (!r.mesh) return;
  const MeshQuality& q = r.quality;
  const double n = std::max(1, q.triangles);
  if (r.topology && r.topology->enabled) {
    const Topology& t = *r.topology;
    out << "composite faces: " << t.composites << " over " << t.face_composite.size() << " faces; curves: "
        << t.count(CurveKind::Virtual) << " crossed (" << r.virtual_reasons.short_curve << " short, "
        << r.virtual_reasons.narrow_face << " beside narrow faces, " << r.virtual_reasons.small_angle
        << " at small angles, " << r.virtual_reasons.smooth << " only smooth), "
        << t.count(CurveKind::Angle) + t.count(CurveKind::Marker) + t.count(CurveKind::User) +
               t.count(CurveKind::Boundary)
        << " kept (" << t.count(CurveKind::Angle) << " sharp, " << t.count(CurveKind::Marker) << " between markers, "
        << t.count(CurveKind::User) << " by the user, " << t.count(CurveKind::Boundary) << " free or non-manifold) in "
        << t.composite_curves << " composite curves\n";
  }
  out << "mesh: " << q.triangles << " triangles, " << q.nodes << " nodes\n"
      << std::setprecision(3) << "quality: worst min angle " << q.worst_angle << " deg; below 12 deg: " << q.below_12
      << " (" << 100.0 * q.below_12 / n << "%; " << q.feature_corner_below_12
      << " at feature corners sharper than 12 deg, " << q.below_12 - q.feature_corner_below_12
      << " elsewhere), below 24 deg: " << q.below_24 << " ("
      << 100.0 * q.below_24 / n
      << "%); size conformity " << 100.0 * q.size_conformity << "%\n"
      << "sized at h_min: " << 100.0 * r.at_h_min_share << "% of the triangles, " << 100.0 * r.at_h_min_area_share
      << "% of the area\n"
      << "topology: " << q.boundary_edges << " boundary edges, " << q.nonmanifold_edges << " non-manifold edges, "
      << q.inverted << " inverted triangles, " << q.self_intersections << " intersecting triangle pairs ("
      << q.local_self_intersections << " within a face or across a shared curve)\n"
      << "size queries: " << r.queries.queries << ", " << r.queries.mean_visited()
      << " background triangles visited on average, " << r.queries.fallbacks << " fallbacks\n";
  if (r.mesh_union.united > 0)
    out << "mesh-level union: " << r.mesh_union.united << " components, " << r.mesh_union.junction_nodes
        << " junction nodes (" << r.mesh_union.junction_nodes_off << " left on the meshes"
        << (r.mesh_union.junction_nodes_unprojected > 0
                ? ", " + std::to_string(r.mesh_union.junction_nodes_unprojected) + " of them off every projection"
                : std::string())
        << "; at most "
        << r.mesh_union.max_junction_gap << " from their CAD surfaces), "
        << r.mesh_union.band_triangles << " triangles remeshed along the cuts\n";
  out << "time:";
  for (const auto& [stage, s] : r.seconds) out << " " << stage << " " << s << " s;";
  out << "\n";
  for (const auto& f : r.mesh->failures) out << "face " << f.face << " not meshed: " << f.reason << "\n";
}

void write_report(const std::string& path, const RunReport& r) {
  std::ofstream out(path);
  if (!out) throw Error("cannot write report '" + path + "'");
  out << report_json(r).dump(2) << "\n";
}

}  // namespace sizemesh
