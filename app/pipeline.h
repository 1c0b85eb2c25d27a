// A run from CAD file to mesh: its options, its result, and the command's
// run() around the stage list of app/stages.h.
#pragma once

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "app/progress.h"
#include "app/run_warnings.h"
#include "app/watchdog.h"
#include "background/background_mesh.h"
#include "cad/model.h"
#include "io/mesh_labels.h"
#include "io/report.h"
#include "mesher/surface_mesh.h"
#include "sizing/params.h"
#include "sizing/size_query.h"
#include "sizing/smooth.h"
#include "sizing/triangle_estimate.h"
#include "topology/topology.h"

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
  // The command line's hard stop (app/watchdog.h): the preparation may take
  // its union budget and this many seconds more before the process ends
  // with an error; 0 none.
  double preparation_grace = 0;
  // A mesh family (sizing/family.h): this many levels, output.L1.ext
  // (coarsest) .. output.Ln.ext, about family_ratio times the triangles per
  // level; 0: one mesh, `output` itself.
  int family = 0;
  double family_ratio = 3.0;
};

// The file of level k of a family: "a/m.vtu" -> "a/m.L2.vtu".
std::string level_path(const std::string& path, int level);

struct RunResult;
// Level `level` of `levels` of a mesh family (sizing/family.h) from a sized
// run (sizing_stages() done): a run of its own holding the model, the
// background and the topology, with the sizes and accuracy rules scaled and
// the estimate made again, ready for meshing_stages().
std::unique_ptr<RunResult> family_level(const RunResult& sized, int level, int levels, double ratio);

// The command line's hard stop around the preparation of `cad`: the union's
// attempts are told to stop at its budget; this catches one that does not
// listen. Disarmed when it goes out of scope.
std::unique_ptr<Watchdog> preparation_hard_stop(const CadFile& cad, const RunOptions& o);

// Exit codes of the sizemesh command.
enum ExitCode { kOk = 0, kError = 1, kUsage = 2, kPartial = 3 };

// Everything one run makes, kept in one place: the report points into it.
struct RunResult {
  explicit RunResult(bool verbose) : clock(verbose, report.seconds) {}
  RunReport report;
  Progress clock;
  std::optional<CadFile> cad;    // from load until prepared
  std::optional<Model> model;
  SizingParams params;           // the options with the config applied, face ids remapped
  BackgroundMesh bg;
  SizeMap sizes;
  TriangleEstimate estimate;
  std::optional<SizeQuery> query;  // once meshed
  SurfaceMesh mesh;
  std::vector<double> target;    // per mesh node: the size map's size there
  std::vector<double> limited_by;  // per mesh node: the rule behind that size (sizing/limit_at.h)
  std::vector<std::string> warnings;  // one line each, without the "sizemesh: warning: " prefix
  bool meshed() const { return report.mesh != nullptr; }
  Topology topology;             // feature and virtual curves, composite faces
  MeshLabels labels() const {
    MeshLabels l = label_faces(*model);
    l.face_composite = topology.face_composite;
    return l;
  }
  // Partial: a face not meshed, components left out of the union (their
  // meshes overlap the rest: not one closed surface), or, where one surface
  // was asked for, triangles that cross, or a surface not closed.
  int exit_code() const {
    const bool apart = model && !model->info().preparation.not_united.empty();
    const bool crossing = model && model->info().preparation.union_requested && report.quality.self_intersections > 0;
    const bool open = model && closed_expected(model->info().preparation) &&
                      report.quality.boundary_edges + report.quality.nonmanifold_edges > 0;
    return mesh.failures.empty() && !apart && !crossing && !open ? kOk : kPartial;
  }
};

std::unique_ptr<RunResult> family_level(const RunResult& sized, int level, int levels, double ratio);

// Paper 3 (sizing_stages(), app/stages.h): loading, preparation, background
// mesh, initial sizes, smoothing and the estimate; prints the sizing summary
// when verbose. Throws Error on bad input.
std::unique_ptr<RunResult> size_model(const RunOptions& options, const WarningSink& warn);

// Paper 4 (meshing_stages()): the size query and the surface mesh, its union,
// quality and target sizes. Throws Error when the size map asks for more
// than --max-triangles.
void mesh_model(RunResult& r, const RunOptions& options, const WarningSink& warn);

// The sizemesh command: both stages and every file asked for. Returns the
// exit code (kPartial when some faces could not be meshed; the rest is still
// written).
int run(const RunOptions& options);

}  // namespace sizemesh
