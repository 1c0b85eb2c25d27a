#include "src/pipeline.h"

#include <chrono>
#include <iostream>

#include "sizing/initial_sizes.h"
#include "src/background_output.h"
#include "src/sizing_report.h"
#include "src/vtu_writer.h"

namespace sizemesh {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

int run(const RunOptions& o) {
  if (!o.output.empty()) check_writable(o.output);
  if (!o.background.empty()) check_writable(o.background);
  auto t0 = std::chrono::steady_clock::now();
  Model model = load_model(o.input, o.load);                         // geometry/
  const double t_load = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  BackgroundMesh bg = build_background_mesh(model, o.tessellation);  // geometry/ (paper 3.1)
  const double t_bg = seconds_since(t0);
  if (o.verbose)
    std::cout << "loaded " << model.info().faces << " faces in " << t_load << " s; background mesh "
              << bg.num_triangles() << " triangles, " << bg.num_vertices() << " vertices in " << t_bg << " s\n";
  SizingParams params = o.sizing;
  if (!o.config.empty()) read_config(o.config, params);
  SizeMap h = initial_sizes(model, bg, params, model.info().diagonal());  // sizing/ (paper 3.2, 3.4)
  SmoothStats smoothing = smooth(bg, h, o.edge_solver);                   // sizing/ (paper 3.3, Eq. 11-12)
  if (o.verbose) print_sizing_summary(bg, h, smoothing, std::cout);
  if (!o.background.empty()) write_background_sizes(o.background, bg, h);
  if (!o.output.empty()) write_background_sizes(o.output, bg, h);
  return kOk;
}

}  // namespace sizemesh
