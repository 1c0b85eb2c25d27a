#include "src/pipeline.h"

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "mesher/target_sizes.h"
#include "sizing/options.h"
#include "sizing/refine_background.h"
#include "sizing/size_query.h"
#include "sizing/triangle_estimate.h"
#include "src/background_output.h"
#include "src/mesh_output.h"
#include "src/progress.h"
#include "src/report.h"
#include "src/sizing_report.h"
#include "src/vtu_writer.h"

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
void warn_local_intersections(const MeshQuality& q) {
  if (q.local_self_intersections == 0) return;
  std::cerr << "sizemesh: warning: " << q.local_self_intersections
            << " pairs of triangles intersect within a face or across a shared curve (faces";
  for (const auto& [a, b] : q.intersecting_faces) std::cerr << " " << a << (a == b ? "" : "/" + std::to_string(b));
  std::cerr << "): the CAD surfaces there likely cross\n";
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
void warn_h_min(const RunReport& r, double h_min) {
  if (r.at_h_min_share > 0.05)
    std::cerr << std::setprecision(3) << "sizemesh: warning: " << 100 * r.at_h_min_share << "% of the triangles ("
              << 100 * r.at_h_min_area_share << "% of the area) are sized at h_min " << h_min
              << ": lower --h-min to resolve those regions, or raise it for fewer triangles\n";
}

// The union is what makes the surface closed: say when it could not be kept.
void warn_preparation(const Preparation& p) {
  if (!p.fallback.empty())
    std::cerr << "sizemesh: warning: geometry preparation incomplete (" << p.fallback
              << "): those components are meshed where they lie\n";
}

}  // namespace

int run(const RunOptions& o) {
  // Refuse what cannot succeed before any long work starts.
  if (!o.output.empty()) check_writable(o.output), check_mesh_format(o.output);
  if (!o.background.empty()) {
    check_writable(o.background);
    if (std::filesystem::path(o.background).extension() != ".vtu")
      throw Error("the background mesh is written as .vtu only, got '" + o.background + "'");
  }
  if (!o.report.empty()) check_writable(o.report);
  SizingParams params = o.sizing;
  if (!o.config.empty()) apply_config(o.config, o.sizing_from_cli, params);

  RunReport report;
  Progress clock(o.verbose, report.seconds);
  const CadFile cad = read_cad(o.input, o.load);                               // geometry/
  clock.lap("load");
  Model model = prepare_model(cad, o.load);                                    // geometry/prepare
  clock.lap("prepare");
  warn_preparation(model.info().preparation);
  std::vector<int> source_face(model.num_faces());
  for (int f = 1; f <= model.num_faces(); ++f) source_face[f - 1] = model.source_face(f);
  remap_face_ids(params, source_face, model.info().sewn_faces);              // sizing/
  const FlowDomain& domain = model.info().domain;
  for (int f = 1; f <= model.num_faces(); ++f)  // the far field and the symmetry plane grade up to their own size
    if (model.boundary(f) != Boundary::Wall && domain.element_size > 0) {
      params.face_h_max[f] = domain.element_size;
      params.edge_graded_faces.insert(f);
    }
  if (model.info().entities_failed > 0)
    std::cerr << "sizemesh: warning: " << model.info().entities_failed
              << " entities could not be read and are left out of the mesh; first: " << model.info().first_failure
              << "\n";
  BackgroundMesh bg = build_background_mesh(model, o.tessellation);            // geometry/ (paper 3.1)
  clock.lap("background");
  SizeMap h = refine_background(model, bg, params, model.info().diagonal(),   // sizing/   (3.2, 3.4)
                                &report.refinement);
  clock.lap("initial_sizes");
  report.smoothing = smooth(bg, h, o.edge_solver);                             // sizing/   (3.3, Eq. 11-12)
  clock.lap("smoothing");
  const TriangleEstimate estimate = estimate_triangles(bg, h.h, h.limit, model.num_faces());  // sizing/
  report.estimated_triangles = estimate.total;
  report.model = &model;
  report.background_triangles = bg.num_triangles();
  report.background_vertices = bg.num_vertices();
  report.sizes = &h;
  if (o.verbose) {
    std::cout << "model: " << model.info().faces << " faces, " << model.info().curves << " curves; background mesh "
              << bg.num_triangles() << " triangles, " << bg.num_vertices() << " vertices ("
              << report.refinement.vertices_before << " from the tessellation, " << report.refinement.edges_split
              << " edges split in " << report.refinement.rounds << " rounds)\n";
    print_sizing_summary(bg, h, report.smoothing, std::cout);
    std::cout << "estimate: about " << static_cast<long long>(estimate.total + 0.5) << " triangles\n";
  }
  if (!o.background.empty()) write_background_sizes(o.background, bg, h);
  if (!o.output.empty()) check_triangle_budget(estimate, params.max_triangles, h);


  SurfaceMesh mesh;
  if (!o.output.empty()) {
    const SizeQuery query = size_query_for(model, bg, h.h);  // sizing/ (4.2)
    MeshOptions meshing = o.meshing;
    meshing.expected_triangles = estimate.per_face;
    meshing.on_face_done = [&clock](int done, int total) { clock.faces(done, total); };
    mesh = mesh_surface(model, query, meshing);                             // mesher/ (4.1)
    clock.lap("meshing");
    report.queries = query.stats();
    report.mesh = &mesh;
    report.quality = mesh_quality(mesh, model, query);
    clock.lap("quality");
    const std::vector<double> target = target_sizes(mesh, query);
    write_mesh(o.output, mesh, label_faces(model), report.quality.min_angle, target);
    clock.lap("output");
    measure_h_min(mesh, target, h.h_min, report);
    if (o.verbose) print_mesh_summary(report, std::cout);
  }
  if (!o.report.empty()) write_report(o.report, report);
  for (const auto& f : mesh.failures)
    std::cerr << "sizemesh: warning: face " << f.face << " was not meshed: " << f.reason << "\n";
  warn_local_intersections(report.quality);
  if (report.mesh) warn_h_min(report, h.h_min);
  return mesh.failures.empty() ? kOk : kPartial;
}

}  // namespace sizemesh
