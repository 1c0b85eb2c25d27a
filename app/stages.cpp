// The stages of a run and the list that runs them (app/stages.h).
#include "app/stages.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <set>
#include <unordered_map>

#include "app/run_warnings.h"
#include "io/sizing_report.h"
#include "mesher/cut_faces.h"
#include "mesher/mesh_surface.h"
#include "mesher/composite_remesh.h"
#include "mesher/mesh_union.h"
#include "mesher/quality.h"
#include "mesher/target_sizes.h"
#include "sizing/initial_sizes.h"
#include "sizing/limit_at.h"
#include "sizing/options.h"
#include "sizing/refine_background.h"
#include "sizing/size_query.h"
#include "topology/wing_features.h"

namespace sizemesh {
namespace {

void load(RunResult& r, const RunOptions& o, const WarningSink&) { r.cad.emplace(read_cad(o.input, o.load)); }

void prepare(RunResult& r, const RunOptions& o, const WarningSink& warn) {
  {
    const auto hard_stop = preparation_hard_stop(*r.cad, o);
    r.model.emplace(prepare_model(*r.cad, o.load));
  }
  r.cad.reset();
  const Model& model = *r.model;
  const ModelInfo& info = model.info();
  if (const int a = info.preparation.half_model_axis; a >= 0 && info.domain.symmetry_axis != a)
    warn(std::string("a half model, open on the plane ") + static_cast<char>('x' + a) +
         " = 0: its mesh has boundary edges there; --symmetry " + static_cast<char>('x' + a) +
         " with a far field closes it");
  warn_left_out(info.preparation.left_out, " is a flat open disk", " are flat open disks",
                " a body passes through (actuator disks)", warn);
  warn_left_out(info.preparation.internal_sheets, " is an open sheet", " are open sheets",
                " inside a body (an internal plane)", warn);
  std::vector<int> source_face(model.num_faces());
  for (int f = 1; f <= model.num_faces(); ++f) source_face[f - 1] = model.source_face(f);
  remap_face_ids(r.params, source_face, info.sewn_faces);
  std::vector<int> domain_faces;  // the far field and the symmetry plane
  for (int f = 1; f <= model.num_faces(); ++f)
    if (model.boundary(f) != Boundary::Wall) domain_faces.push_back(f);
  size_domain_faces(r.params, domain_faces, info.domain.element_size);
  if (!info.domain.farfield.empty() && info.domain.inside_points.empty())
    warn("no closed solid of the body was found inside the far field: a volume mesher cannot tell the body's "
         "inside from the fluid around it (see --info for free curves)");
  for (const auto& line : info.read_repairs) warn(line);
  if (info.entities_failed > 0)
    warn(std::to_string(info.entities_failed) + " entities could not be read and are left out of the mesh; first: " +
         info.first_failure);
}

// Feature and virtual curves (topology/): faces of different components,
// boundary kinds or user settings never join one composite face; curves with
// their own settings stay.
void topology(RunResult& r, const RunOptions&, const WarningSink&) {
  const Model& model = *r.model;
  const MeshLabels labels = label_faces(model);
  const SizingParams& p = r.params;
  std::map<std::string, int> class_id;
  std::vector<int> face_class(model.num_faces());
  for (int f = 1; f <= model.num_faces(); ++f) {
    const MeshLabels::Marker& m = labels.markers.at(labels.marker_of(f));
    std::string key = m.component + "/" + std::to_string(static_cast<int>(m.kind));
    if (p.face_size.count(f) || p.face_phi_c_deg.count(f) || p.face_mu_d.count(f) || p.face_beta.count(f))
      key += "/face " + std::to_string(f);
    face_class[f - 1] = class_id.emplace(key, static_cast<int>(class_id.size())).first->second;
  }
  std::set<int> kept;
  for (const auto& e : p.curve_size) kept.insert(e.first);
  for (const auto& e : p.curve_phi_c_deg) kept.insert(e.first);
  r.topology = build_topology(model, face_class, kept, p.feature_angle_deg, p.composite);
  r.report.topology = &r.topology;
  r.params.wing = find_wing_features(model, r.topology);
  r.report.wing = &r.params.wing;
  if (r.topology.enabled) {
    r.params.virtual_curve.assign(model.num_curves(), 0);
    for (int c = 1; c <= model.num_curves(); ++c) r.params.virtual_curve[c - 1] = !r.topology.hard(c);
    r.params.chain_length = r.topology.chain_length;
  }
}

void background(RunResult& r, const RunOptions& o, const WarningSink& warn) {
  r.bg = build_background_mesh(*r.model, o.tessellation);
  warn_faces_without_background(r.bg, warn);
}

void initial(RunResult& r, const RunOptions&, const WarningSink&) {
  r.sizes = initial_sizes(*r.model, r.bg, r.params, r.model->info().diagonal());
}

void refine(RunResult& r, const RunOptions&, const WarningSink&) {
  refine_background(*r.model, r.bg, r.params, r.model->info().diagonal(), r.sizes, &r.report.refinement);
}

void smoothing(RunResult& r, const RunOptions& o, const WarningSink&) {
  r.report.smoothing = smooth(r.bg, r.sizes, o.edge_solver);
}

void estimate(RunResult& r, const RunOptions& o, const WarningSink&) {
  const Model& model = *r.model;
  RunReport& report = r.report;
  r.estimate = estimate_triangles(r.bg, r.sizes.h, r.sizes.limit, model.num_faces());
  report.estimated_triangles = r.estimate.total;
  report.model = &model;
  report.background_triangles = r.bg.num_triangles();
  report.background_vertices = r.bg.num_vertices();
  report.sizes = &r.sizes;
  if (!o.verbose) return;
  std::cout << "model: " << model.info().faces << " faces, " << model.info().curves << " curves; background mesh "
            << r.bg.num_triangles() << " triangles, " << r.bg.num_vertices() << " vertices ("
            << report.refinement.vertices_before << " from the tessellation, " << report.refinement.edges_split
            << " edges split in " << report.refinement.rounds << " rounds, " << report.refinement.flips
            << " edges flipped)\n";
  print_sizing_summary(r.bg, r.sizes, report.smoothing, std::cout);
  const WingFeatures& w = r.params.wing;
  if (!w.empty()) {
    std::cout << "wing features: " << w.leading.size() << " leading edge curves (" << w.leading_length << " long), "
              << w.trailing.size() << " trailing edge curves (" << w.trailing_length << "), chord " << w.chord_min
              << " to " << w.chord_max;
    if (!w.bases.empty()) {
      double lo = INFINITY, hi = 0;
      for (const WingFeatures::Base& b : w.bases) lo = std::min(lo, b.width_min), hi = std::max(hi, b.width_max);
      std::cout << ", " << w.bases.size() << " blunt trailing edge base" << (w.bases.size() > 1 ? "s" : "") << " ("
                << lo << " to " << hi << " wide)";
    }
    if (!w.tips.empty()) std::cout << ", " << w.tips.size() << " tip" << (w.tips.size() > 1 ? "s" : "");
    std::cout << "; chordwise spacing ";
    if (r.params.le_spacing > 0 || r.params.te_spacing > 0)
      std::cout << r.params.le_spacing << " and " << r.params.te_spacing << " of the local chord";
    else
      std::cout << "off (--le-spacing, --te-spacing, --aero)";
    if (!w.bases.empty() && r.params.te_cells > 0) std::cout << "; " << r.params.te_cells << " elements across a base";
    if (!w.tips.empty() && r.params.tip_spacing > 0) std::cout << "; " << r.params.tip_spacing << " of the chord on tips";
    std::cout << "\n";
  }
  std::cout << "estimate: about " << static_cast<long long>(r.estimate.total + 0.5) << " triangles\n";
}

void size_query(RunResult& r, const RunOptions&, const WarningSink&) {
  check_triangle_budget(r.estimate, r.params.max_triangles, r.sizes);
  const Model& model = *r.model;
  r.query.emplace(size_query_for(model, r.bg, r.sizes.h));
  r.query->set_accuracy(accuracy_rules(r.params, r.sizes.h_min, model.num_faces()));
}

MeshOptions meshing_options(RunResult& r, const RunOptions& o) {
  MeshOptions meshing = o.meshing;
  meshing.expected_triangles = r.estimate.per_face;
  meshing.on_face_done = [&r](int done, int total) { r.clock.faces(done, total); };
  return meshing;
}

void meshing(RunResult& r, const RunOptions& o, const WarningSink&) {
  r.mesh = mesh_surface(*r.model, *r.query, meshing_options(r, o));
}

// The components the B-rep union left out, united with the rest as meshes
// (mesher/mesh_union.h); what it cannot take stays apart (exit 3).
void mesh_union(RunResult& r, const RunOptions& o, const WarningSink& warn) {
  Model& model = *r.model;
  const Preparation& p = model.info().preparation;
  if (!p.not_united.empty()) {
    const std::vector<int> left = p.not_united;
    if (model.fluid_side() < 0) {
      for (int k : left) model.record_mesh_union(k, "not tried inside a flow domain");
    } else {
      std::unordered_map<int, int> component_of;  // sewn face -> index in `left`
      for (size_t i = 0; i < left.size(); ++i)
        for (int f : p.components[left[i] - 1].face_ids) component_of[f] = static_cast<int>(i);
      std::vector<std::vector<int>> parts(left.size());
      for (int f = 1; f <= model.num_faces(); ++f)
        if (const auto it = component_of.find(model.source_face(f)); it != component_of.end())
          parts[it->second].push_back(f);
      r.report.mesh_union = unite_meshes(r.mesh, model, *r.query, parts);
      r.report.cut_faces = remesh_cut_faces(r.mesh, model, *r.query, meshing_options(r, o), r.report.mesh_union);
      for (size_t i = 0; i < left.size(); ++i) model.record_mesh_union(left[i], r.report.mesh_union.failures[i]);
    }
  }
  warn_not_united(model.info().preparation, warn);
}

// Composite faces meshed as one: the mesh re-meshed across virtual curves.
void composite(RunResult& r, const RunOptions&, const WarningSink&) {
  r.report.composite = remesh_composites(r.mesh, *r.model, *r.query, r.topology, &r.report.mesh_union.junction);
  r.report.virtual_reasons = classify_virtual_curves(*r.model, r.topology, [&](int f, const Vec2& uv) {
    int hint = -1;
    return r.query->at(f, uv, hint);
  });
}

void quality(RunResult& r, const RunOptions&, const WarningSink& warn) {
  const Model& model = *r.model;
  r.report.queries = r.query->stats();
  r.report.mesh = &r.mesh;
  const auto kept = kept_edges(r.mesh, model, r.topology);
  r.report.quality = mesh_quality(r.mesh, model, *r.query, &kept);
  r.target = target_sizes(r.mesh, *r.query);
  // The rule behind each node's size, as the background shows it.
  r.limited_by.assign(r.mesh.xyz.size(), -1.0);
  std::vector<char> done(r.mesh.xyz.size(), 0);
  int hint = -1;
  for (size_t t = 0; t < r.mesh.tris.size(); ++t) {
    if (t > 0 && r.mesh.tri_face[t] != r.mesh.tri_face[t - 1]) hint = -1;  // hints are per face
    for (int k = 0; k < 3; ++k) {
      const int n = r.mesh.tris[t][k];
      if (done[n]) continue;
      done[n] = 1;
      r.limited_by[n] = limit_at(*r.query, r.bg, r.sizes, r.mesh.tri_face[t], r.mesh.tri_uv[t][k], r.mesh.xyz[n], hint);
    }
  }
  measure_h_min(r.mesh, r.target, r.limited_by, r.sizes.h_min, r.report);
  for (const auto& f : r.mesh.failures) warn("face " + std::to_string(f.face) + " was not meshed: " + f.reason);
  warn_local_intersections(r.report.quality, warn);
  warn_crossings(r.report.quality, model.info().preparation, warn);
  warn_open(r.report.quality, model.info().preparation, !r.mesh.failures.empty(), warn);
  warn_h_min(r.report, r.sizes.h_min, warn);
}

Stages::iterator find(Stages& stages, const std::string& name) {
  const auto it = std::find_if(stages.begin(), stages.end(), [&](const Stage& s) { return s.name == name; });
  if (it == stages.end()) throw Error("no stage named '" + name + "' in this run");
  return it;
}

}  // namespace

Stages sizing_stages() {
  return {{"load", load},           {"prepare", prepare},
          {"topology", topology},     {"background", background}, {"initial_sizes", initial},
          {"refine_background", refine}, {"smoothing", smoothing},
          {"estimate", estimate}};
}

Stages meshing_stages() {
  return {{"size_query", size_query}, {"meshing", meshing}, {"mesh_union", mesh_union},
          {"composite", composite},   {"quality", quality}};
}

Stages all_stages() {
  Stages s = sizing_stages();
  for (Stage& m : meshing_stages()) s.push_back(std::move(m));
  return s;
}

Stages until(Stages stages, const std::string& last) {
  stages.erase(find(stages, last) + 1, stages.end());
  return stages;
}

Stages from(Stages stages, const std::string& first) {
  stages.erase(stages.begin(), find(stages, first));
  return stages;
}

Stages replaced(Stages stages, const std::string& name, Stage::Step step) {
  find(stages, name)->step = std::move(step);
  return stages;
}

Stages without(Stages stages, const std::string& name) {
  stages.erase(find(stages, name));
  return stages;
}

std::unique_ptr<RunResult> start_run(const RunOptions& o) {
  auto r = std::make_unique<RunResult>(o.verbose);
  r->params = o.sizing;
  if (!o.config.empty()) apply_config(o.config, o.sizing_from_cli, r->params);
  return r;
}

void run_stages(RunResult& r, const RunOptions& o, const WarningSink& warn, const Stages& stages) {
  for (const Stage& s : stages) {
    const long long before = r.model ? r.model->surface_evaluations() : 0;
    s.step(r, o, warn);
    r.clock.lap(s.name);
    r.report.evaluations.emplace_back(s.name, (r.model ? r.model->surface_evaluations() : 0) - before);
  }
}

}  // namespace sizemesh
