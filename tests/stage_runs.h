// Runs of the command's stage list (app/stages.h) for tests and benches: the
// stages the command runs, stopped early or resumed, never wired again by hand.
#pragma once

#include <memory>
#include <string>

#include "app/stages.h"
#include "tests/test_models.h"

namespace sizemesh::test {

inline const WarningSink& quiet() {
  static const WarningSink sink = [](const std::string&) {};
  return sink;
}

// The command's options for a quiet run of a test model (tests/data).
inline RunOptions run_options(const std::string& file) {
  RunOptions o;
  o.input = model_path(file);
  o.verbose = false;
  return o;
}

// A run of o's model through the command's stages, up to and including `last`.
inline std::unique_ptr<RunResult> run_until(const RunOptions& o, const std::string& last = "quality") {
  std::unique_ptr<RunResult> r = start_run(o);
  run_stages(*r, o, quiet(), until(all_stages(), last));
  return r;
}

// A run of a model made otherwise (a shape built with OpenCASCADE, sizing
// parameters in o.sizing): the command's stages after the preparation.
inline std::unique_ptr<RunResult> run_model(const Model& model, const RunOptions& o,
                                            const std::string& last = "quality") {
  std::unique_ptr<RunResult> r = start_run(o);
  r->model.emplace(model);
  run_stages(*r, o, quiet(), until(from(all_stages(), "topology"), last));
  return r;
}

// The rest of a run stopped early: its stages from `first` to `last`.
inline void run_on(RunResult& r, const RunOptions& o, const std::string& first, const std::string& last = "quality") {
  run_stages(r, o, quiet(), until(from(all_stages(), first), last));
}

}  // namespace sizemesh::test
