#include "src/pipeline.h"

#include <chrono>
#include <iostream>

#include "src/background_output.h"
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
  if (!o.background.empty()) write_background(o.background, bg);
  if (!o.output.empty()) write_background(o.output, bg);
  return kOk;
}

}  // namespace sizemesh
