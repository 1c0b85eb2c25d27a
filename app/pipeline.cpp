#include "app/pipeline.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "app/progress.h"
#include "app/stages.h"
#include "app/watchdog.h"
#include "io/background_output.h"
#include "io/mesh_output.h"
#include "io/report.h"
#include "sizing/family.h"
#include "sizing/triangle_estimate.h"

namespace sizemesh {

namespace {

void print_to_stderr(const std::string& line) { std::cerr << "sizemesh: warning: " << line << "\n"; }

// The levels of a family from one sized run, each meshed and written (with
// its report) before the next starts; the exit code is the worst level's.
int run_family(const RunResult& sized, const RunOptions& o, const WarningSink& warn) {
  std::vector<int> triangles;
  int code = kOk;
  for (int level = 1; level <= o.family; ++level) {
    const std::unique_ptr<RunResult> r = family_level(sized, level, o.family, o.family_ratio);
    if (o.verbose)
      std::cout << "level " << level << " of " << o.family << ": sizes x "
                << family_scale(level, o.family, o.family_ratio) << "\n";
    mesh_model(*r, o, warn);
    write_mesh(level_path(o.output, level), r->mesh, r->labels(), r->report.quality, r->target, r->limited_by);
    r->clock.lap("output");
    if (o.verbose) print_mesh_summary(r->report, std::cout);
    if (!o.report.empty()) write_report(level_path(o.report, level), r->report);
    triangles.push_back(r->report.quality.triangles);
    code = std::max(code, r->exit_code());
  }
  if (o.verbose) {
    std::cout << "family:";
    for (size_t k = 0; k < triangles.size(); ++k) {
      std::cout << (k ? ";" : "") << " L" << k + 1 << " " << triangles[k] << " triangles";
      if (k > 0) std::cout << " (" << std::setprecision(3) << double(triangles[k]) / std::max(1, triangles[k - 1]) << "x)";
    }
    std::cout << "\n";
  }
  return code;
}

}  // namespace

std::unique_ptr<RunResult> family_level(const RunResult& sized, int level, int levels, double ratio) {
  const double s = family_scale(level, levels, ratio);
  auto r = std::make_unique<RunResult>(sized.clock.enabled());
  r->report = sized.report;
  r->model = sized.model;
  r->params = scaled_rules(sized.params, s);
  r->bg = sized.bg;
  r->sizes = scaled_map(sized.sizes, s);
  r->topology = sized.topology;
  r->warnings = sized.warnings;
  r->estimate = estimate_triangles(r->bg, r->sizes.h, r->sizes.limit, r->model->num_faces());
  r->report.estimated_triangles = r->estimate.total;
  r->report.model = &*r->model;
  r->report.sizes = &r->sizes;
  r->report.topology = &r->topology;
  r->report.wing = &r->params.wing;
  r->report.mesh = nullptr;
  return r;
}

std::string level_path(const std::string& path, int level) {
  const std::filesystem::path p(path);
  std::filesystem::path out = p;
  out.replace_filename(p.stem().string() + ".L" + std::to_string(level) + p.extension().string());
  return out.string();
}

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
  std::unique_ptr<RunResult> r = start_run(o);
  run_stages(*r, o, warn, sizing_stages());
  return r;
}

void mesh_model(RunResult& r, const RunOptions& o, const WarningSink& warn) {
  run_stages(r, o, warn, meshing_stages());
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
  if (o.family > 0 && o.output.empty()) throw Error("a mesh family (--family) needs an output file (-o)");
  std::unique_ptr<RunResult> r = size_model(o, warn);
  if (o.output.empty()) warn_not_united(r->model->info().preparation, warn);
  if (!o.background.empty()) write_background_sizes(o.background, r->bg, r->sizes, &r->params.wing);
  if (!o.output.empty() && o.family > 0) {
    meshing = true;
    const int code = run_family(*r, o, warn);
    for (const auto& line : later) print_to_stderr(line);
    return code;
  }
  if (!o.output.empty()) {
    meshing = true;
    mesh_model(*r, o, warn);
    write_mesh(o.output, r->mesh, r->labels(), r->report.quality, r->target, r->limited_by);
    r->clock.lap("output");
    if (o.verbose) print_mesh_summary(r->report, std::cout);
  }
  if (!o.report.empty()) write_report(o.report, r->report);
  for (const auto& line : later) print_to_stderr(line);
  return r->exit_code();
}

}  // namespace sizemesh
