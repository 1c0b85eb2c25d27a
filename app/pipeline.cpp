#include "app/pipeline.h"

#include <filesystem>
#include <iostream>
#include <sstream>

#include "app/progress.h"
#include "app/stages.h"
#include "app/watchdog.h"
#include "io/background_output.h"
#include "io/mesh_output.h"
#include "io/report.h"

namespace sizemesh {

namespace {

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
  std::unique_ptr<RunResult> r = size_model(o, warn);
  if (o.output.empty()) warn_not_united(r->model->info().preparation, warn);
  if (!o.background.empty()) write_background_sizes(o.background, r->bg, r->sizes);
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
