#include "src/pipeline.h"

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <unordered_map>

#include "mesher/cut_faces.h"
#include "mesher/mesh_surface.h"
#include "mesher/mesh_union.h"
#include "mesher/quality.h"
#include "mesher/target_sizes.h"
#include "sizing/options.h"
#include "sizing/initial_sizes.h"
#include "sizing/refine_background.h"
#include "sizing/size_query.h"
#include "sizing/triangle_estimate.h"
#include "src/background_output.h"
#include "src/mesh_output.h"
#include "src/progress.h"
#include "src/report.h"
#include "src/sizing_report.h"
#include "src/vtu_writer.h"
#include "src/watchdog.h"

namespace sizemesh {

namespace {

// Refuses a size map that asks for more triangles than the user allows,
// naming the option that drives the count.
void check_triangle_budget(const TriangleEstimate& e, double max_triangles, const SizeMap& h) {
  if (e.total <= max_triangles) return;
  const char* option = "--h-min";
  switch (e.dominant()) {
    case Limit::HMax: option = "--h-max"; break;
    case Limit::Curvature: option = "--phi-c or --deviation"; break;
    case Limit::FaceProximity:
    case Limit::CurveLength:
    case Limit::Gap: option = "--mu-d, --no-gaps or --h-min"; break;
    case Limit::Thickness: option = "--gap-side fluid, --mu-d or --h-min"; break;
    case Limit::User: option = "the config's local sizes"; break;
    case Limit::HMin: option = "--h-min"; break;
    case Limit::FarField: option = "--farfield-h"; break;
  }
  std::ostringstream msg;
  msg << std::setprecision(3) << "the size map asks for about " << e.total << " triangles, more than --max-triangles "
      << max_triangles << " (h_min " << h.h_min << ", h_max " << h.h_max << "); most come from sizes set by "
      << limit_name(e.dominant()) << ": raise " << option << ", or --max-triangles";
  throw Error(msg.str());
}

// Triangles crossing within a face or across a shared curve: the front never
// makes them where the CAD is sound, so they point at faces that cross
// themselves or their neighbours.
void warn_local_intersections(const MeshQuality& q, const WarningSink& warn) {
  if (q.local_self_intersections == 0) return;
  std::ostringstream msg;
  msg << q.local_self_intersections << " pairs of triangles intersect within a face or across a shared curve (faces";
  for (const auto& [a, b] : q.intersecting_faces) msg << " " << a << (a == b ? "" : "/" + std::to_string(b));
  msg << "): the CAD surfaces there likely cross";
  warn(msg.str());
}

// Triangles of faces that share no curve crossing each other where the
// components were united: the surface is not one closed body (exit 3).
void warn_crossings(const MeshQuality& q, const Preparation& p, const WarningSink& warn) {
  const long long n = q.self_intersections - q.local_self_intersections;
  if (n == 0 || !p.union_requested || !p.not_united.empty()) return;
  std::ostringstream msg;
  msg << n << " pairs of triangles of faces that share no curve intersect (faces";
  for (const auto& [a, b] : q.crossing_faces) msg << " " << a << "/" << b;
  msg << "): the united surface crosses itself there (exit 3)";
  warn(msg.str());
}

// Boundary or non-manifold edges where one closed surface was asked for,
// every face meshed and every component united (exit 3).
void warn_open(const MeshQuality& q, const Preparation& p, bool faces_failed, const WarningSink& warn) {
  if (q.boundary_edges + q.nonmanifold_edges == 0 || !closed_expected(p) || !p.not_united.empty() || faces_failed ||
      q.self_intersections > q.local_self_intersections)
    return;
  std::ostringstream msg;
  msg << "the united surface is not closed: " << q.boundary_edges << " boundary and " << q.nonmanifold_edges
      << " non-manifold edges (faces";
  for (int f : q.open_faces) msg << " " << f;
  msg << ") (exit 3)";
  warn(msg.str());
}

// Shares of the triangles and of the area whose target size is within 5% of h_min.
void measure_h_min(const SurfaceMesh& m, const std::vector<double>& target, double h_min, RunReport& r) {
  double n = 0, area = 0, total = 0;
  for (const auto& t : m.tris) {
    const double a = 0.5 * (m.xyz[t[1]] - m.xyz[t[0]]).cross(m.xyz[t[2]] - m.xyz[t[0]]).norm();
    total += a;
    if ((target[t[0]] + target[t[1]] + target[t[2]]) / 3 <= 1.05 * h_min) n += 1, area += a;
  }
  r.at_h_min_share = m.tris.empty() ? 0 : n / m.tris.size();
  r.at_h_min_area_share = total > 0 ? area / total : 0;
}

// One warning line when h_min sets more than 5% of the triangles.
void warn_h_min(const RunReport& r, double h_min, const WarningSink& warn) {
  if (!(r.at_h_min_share > 0.05)) return;
  std::ostringstream msg;
  msg << std::setprecision(3) << 100 * r.at_h_min_share << "% of the triangles (" << 100 * r.at_h_min_area_share
      << "% of the area) are sized at h_min " << h_min
      << ": lower --h-min to resolve those regions, or raise it for fewer triangles";
  warn(msg.str());
}

// The far field and the symmetry plane grade up to their own size, along
// background edges only (sizing/params.h).
void size_domain_faces(const Model& model, SizingParams& params) {
  const FlowDomain& domain = model.info().domain;
  if (!(domain.element_size > 0)) return;
  for (int f = 1; f <= model.num_faces(); ++f)
    if (model.boundary(f) != Boundary::Wall) {
      params.face_h_max[f] = domain.element_size;
      params.edge_graded_faces.insert(f);
    }
}

}  // namespace

// One line naming the components the union left out (the run ends with exit 3).
void warn_not_united(const Preparation& p, const WarningSink& warn) {
  if (p.not_united.empty()) return;
  std::ostringstream msg;
  msg << (p.not_united.size() == 1 ? "component" : "components");
  for (size_t i = 0; i < p.not_united.size(); ++i) {
    const Component& c = p.components[p.not_united[i] - 1];
    msg << (i ? "; " : " ") << p.not_united[i] << " (" << c.faces << " faces, "
        << c.route.substr(c.route.find(':') == std::string::npos ? 0 : c.route.find(':') + 2) << ")";
  }
  msg << " could not be united with the rest: meshed where they lie, so the surface is not one closed body (exit 3)";
  warn(msg.str());
}

namespace {

// The components the B-rep union left out, united with the rest as meshes
// (mesher/mesh_union.h); what it cannot take stays apart (exit 3).
void unite_at_mesh_level(RunResult& r, const MeshOptions& meshing) {
  Model& model = *r.model;
  const Preparation& p = model.info().preparation;
  if (p.not_united.empty()) return;
  const std::vector<int> left = p.not_united;
  if (model.fluid_side() < 0) {
    for (int k : left) model.record_mesh_union(k, "not tried inside a flow domain");
    return;
  }
  std::unordered_map<int, int> component_of;  // sewn face -> index in `left`
  for (size_t i = 0; i < left.size(); ++i)
    for (int f : p.components[left[i] - 1].face_ids) component_of[f] = static_cast<int>(i);
  std::vector<std::vector<int>> parts(left.size());
  for (int f = 1; f <= model.num_faces(); ++f)
    if (const auto it = component_of.find(model.source_face(f)); it != component_of.end())
      parts[it->second].push_back(f);
  r.report.mesh_union = unite_meshes(r.mesh, model, *r.query, parts);
  r.report.cut_faces = remesh_cut_faces(r.mesh, model, *r.query, meshing, r.report.mesh_union);
  for (size_t i = 0; i < left.size(); ++i) model.record_mesh_union(left[i], r.report.mesh_union.failures[i]);
}

// One line naming the open components left out of the wetted surface,
// `one`/`many` saying what they are and `why` where they lie.
void warn_left_out(const std::vector<int>& ks, const char* one, const char* many, const char* why,
                   const WarningSink& warn) {
  if (ks.empty()) return;
  std::ostringstream msg;
  msg << (ks.size() == 1 ? "component" : "components");
  for (size_t i = 0; i < ks.size(); ++i) msg << (i ? ", " : " ") << ks[i];
  msg << (ks.size() == 1 ? one : many) << why << ": no wall, left out of the wetted surface";
  warn(msg.str());
}

void print_to_stderr(const std::string& line) { std::cerr << "sizemesh: warning: " << line << "\n"; }

}  // namespace

std::unique_ptr<Watchdog> preparation_hard_stop(const CadFile& cad, const RunOptions& o) {
  if (!(o.preparation_grace > 0)) return nullptr;
  const double budget = union_budget(cad, o.load);
  std::ostringstream msg;
  msg << "the preparation of '" << o.input << "' did not end within " << budget + o.preparation_grace
      << " s (its repair and union have a --union-seconds budget of " << budget
      << " s); rerun with --no-union to mesh the components where they lie";
  return std::make_unique<Watchdog>(budget + o.preparation_grace, msg.str());
}

std::unique_ptr<RunResult> size_model(const RunOptions& o, const WarningSink& warn) {
  auto r = std::make_unique<RunResult>(o.verbose);
  RunReport& report = r->report;
  r->params = o.sizing;
  if (!o.config.empty()) apply_config(o.config, o.sizing_from_cli, r->params);
  const CadFile cad = read_cad(o.input, o.load);                               // geometry/
  r->clock.lap("load");
  {
    const auto hard_stop = preparation_hard_stop(cad, o);
    r->model.emplace(prepare_model(cad, o.load));                              // geometry/prepare
  }
  const Model& model = *r->model;
  r->clock.lap("prepare");
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
  remap_face_ids(r->params, source_face, info.sewn_faces);                    // sizing/
  size_domain_faces(model, r->params);
  if (!info.domain.farfield.empty() && info.domain.inside_points.empty())
    warn("no closed solid of the body was found inside the far field: a volume mesher cannot tell the body's "
         "inside from the fluid around it (see --info for free curves)");
  for (const auto& line : info.read_repairs) warn(line);
  if (info.entities_failed > 0)
    warn(std::to_string(info.entities_failed) + " entities could not be read and are left out of the mesh; first: " +
         info.first_failure);
  r->bg = build_background_mesh(model, o.tessellation);                      // geometry/ (paper 3.1)
  r->clock.lap("background");
  r->sizes = initial_sizes(model, r->bg, r->params, info.diagonal());       // sizing/   (3.2, 3.4)
  r->clock.lap("initial_sizes");
  refine_background(model, r->bg, r->params, info.diagonal(), r->sizes,     // sizing/   (beyond the paper)
                    &report.refinement);
  r->clock.lap("refine_background");
  report.smoothing = smooth(r->bg, r->sizes, o.edge_solver);                 // sizing/   (3.3, Eq. 11-12)
  r->clock.lap("smoothing");
  r->estimate = estimate_triangles(r->bg, r->sizes.h, r->sizes.limit, model.num_faces());  // sizing/
  report.estimated_triangles = r->estimate.total;
  report.model = &model;
  report.background_triangles = r->bg.num_triangles();
  report.background_vertices = r->bg.num_vertices();
  report.sizes = &r->sizes;
  if (o.verbose) {
    std::cout << "model: " << info.faces << " faces, " << info.curves << " curves; background mesh "
              << r->bg.num_triangles() << " triangles, " << r->bg.num_vertices() << " vertices ("
              << report.refinement.vertices_before << " from the tessellation, " << report.refinement.edges_split
              << " edges split in " << report.refinement.rounds << " rounds, " << report.refinement.flips
              << " edges flipped)\n";
    print_sizing_summary(r->bg, r->sizes, report.smoothing, std::cout);
    std::cout << "estimate: about " << static_cast<long long>(r->estimate.total + 0.5) << " triangles\n";
  }
  return r;
}

void mesh_model(RunResult& r, const RunOptions& o, const WarningSink& warn) {
  check_triangle_budget(r.estimate, r.params.max_triangles, r.sizes);
  const Model& model = *r.model;
  r.query.emplace(size_query_for(model, r.bg, r.sizes.h));                  // sizing/ (4.2)
  MeshOptions meshing = o.meshing;
  meshing.expected_triangles = r.estimate.per_face;
  set_accuracy(meshing, r.params, r.sizes.h_min, model.num_faces());
  meshing.on_face_done = [&r](int done, int total) { r.clock.faces(done, total); };
  r.mesh = mesh_surface(model, *r.query, meshing);                          // mesher/ (4.1)
  r.clock.lap("meshing");
  if (!model.info().preparation.not_united.empty()) {
    unite_at_mesh_level(r, meshing);                                                // mesher/mesh_union
    r.clock.lap("mesh union");
  }
  warn_not_united(model.info().preparation, warn);
  r.report.queries = r.query->stats();
  r.report.mesh = &r.mesh;
  r.report.quality = mesh_quality(r.mesh, model, *r.query);
  r.clock.lap("quality");
  r.target = target_sizes(r.mesh, *r.query);
  measure_h_min(r.mesh, r.target, r.sizes.h_min, r.report);
  for (const auto& f : r.mesh.failures) warn("face " + std::to_string(f.face) + " was not meshed: " + f.reason);
  warn_local_intersections(r.report.quality, warn);
  warn_crossings(r.report.quality, model.info().preparation, warn);
  warn_open(r.report.quality, model.info().preparation, !r.mesh.failures.empty(), warn);
  warn_h_min(r.report, r.sizes.h_min, warn);
}

int run(const RunOptions& o) {
  // Refuse what cannot succeed before any long work starts.
  if (!o.output.empty()) check_writable(o.output), check_mesh_format(o.output);
  if (!o.background.empty()) {
    check_writable(o.background);
    if (std::filesystem::path(o.background).extension() != ".vtu")
      throw Error("the background mesh is written as .vtu only, got '" + o.background + "'");
  }
  if (!o.report.empty()) check_writable(o.report);
  // Warnings about the mesh come after its summary; the others at once.
  std::vector<std::string> later;
  bool meshing = false;
  const WarningSink warn = [&](const std::string& line) {
    if (meshing) later.push_back(line);
    else print_to_stderr(line);
  };
  std::unique_ptr<RunResult> r = size_model(o, warn);
  if (o.output.empty()) warn_not_united(r->model->info().preparation, warn);
  if (!o.background.empty()) write_background_sizes(o.background, r->bg, r->sizes);
  if (!o.output.empty()) {
    meshing = true;
    mesh_model(*r, o, warn);
    write_mesh(o.output, r->mesh, r->labels(), r->report.quality, r->target);
    r->clock.lap("output");
    if (o.verbose) print_mesh_summary(r->report, std::cout);
  }
  if (!o.report.empty()) write_report(o.report, r->report);
  for (const auto& line : later) print_to_stderr(line);
  return r->exit_code();
}

}  // namespace sizemesh
