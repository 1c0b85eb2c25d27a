// The paper's flow from CAD file to mesh, one named step after another.
#pragma once

#include <set>
#include <string>

#include "geometry/background_mesh.h"
#include "geometry/model.h"
#include "mesher/surface_mesh.h"
#include "sizing/params.h"
#include "sizing/smooth.h"

namespace sizemesh {

struct RunOptions {
  std::string input;
  std::string output;       // mesh: .vtu, .msh or .stl; empty: no mesh is made
  std::string background;   // background mesh with its size fields (.vtu); empty: none
  std::string report;       // JSON report; empty: none
  LoadOptions load;
  BackgroundOptions tessellation;
  SizingParams sizing;
  std::string config;       // JSON config (globals and local sizes); empty: none
  std::set<std::string> sizing_from_cli;  // keys of sizing options given as flags: they win over the config
  EdgeSolver edge_solver = EdgeSolver::Dijkstra;
  MeshOptions meshing;
  bool verbose = true;
};

// Exit codes of the sizemesh command.
enum ExitCode { kOk = 0, kError = 1, kUsage = 2, kPartial = 3 };

// Runs the whole pipeline; throws Error on bad input. Returns the exit code
// (kPartial when some faces could not be meshed; the rest is still written).
int run(const RunOptions& options);

}  // namespace sizemesh
