// The options of one run, once: their flags, defaults, ranges and help text
// for the sizemesh command, which the Python module reuses by turning its
// keyword arguments into the same flags (so names, defaults, checks and
// messages cannot drift apart).
#pragma once

#include <CLI/CLI.hpp>

#include <map>
#include <string>
#include <vector>

#include "app/pipeline.h"

namespace sizemesh {

// What the parser fills in; `finish_run_options` completes `options` after parsing.
struct RunCommandLine {
  RunOptions options;
  bool info_only = false;
  std::map<std::string, std::string> words;  // choice options: the word given
  std::string farfield = "none", symmetry = "none", smoother = "exact";
  std::vector<std::string> mesh_union;  // component numbers, or "all"
  std::vector<std::string> sources;     // --source texts (sizing/sources.h)
  bool aero = false;                    // --aero: the workshops' spacings where not given
  CLI::Option* symmetry_at = nullptr;
};

// Adds every option of a run (and the model positional) to `app`.
void add_run_options(CLI::App& app, RunCommandLine& cl);

// After app.parse(): choice words into their settings, and which sizing
// options the command line gave (they win over the config file).
void finish_run_options(const CLI::App& app, RunCommandLine& cl);

// The command-line arguments for keyword arguments (name and value as text,
// or "true"/"false" for switches; a name may come more than once, for a
// repeatable flag): `h_min` -> `--h-min`, `sew=false` -> `--no-sew`. Throws
// Error on a name the command line does not have.
std::vector<std::string> arguments_for(const CLI::App& app,
                                       const std::vector<std::pair<std::string, std::string>>& kwargs);

}  // namespace sizemesh
