// The run as a list of named stages over one context, in the paper's order
// (as OCCT's IMeshTools_MeshBuilder runs its stages): each stage reads and
// fills the RunResult and is timed under its name (the report's "seconds",
// the progress lines). The command, the Python module, the tests and the
// benches all run this list; a test or a bench swaps one stage, drops one or
// stops early instead of wiring the steps again.
//
//   load               read the CAD file                         cad/
//   prepare            one wetted surface, the flow domain       cad/
//   topology           feature curves, composite faces           topology/
//   background         the classified background mesh (3.1)      background/
//   initial_sizes      curvature, proximity, user sizes (3.2, 3.4) sizing/
//   refine_background  split edges too long for a graded size    sizing/
//   smoothing          the gradient bound (3.3, Eq. 11-12)       sizing/
//   estimate           triangles the map asks for                sizing/
//   size_query         the walk-through query (4.2), accuracy    sizing/
//   meshing            curves, fronts, optimisation (4.1)        mesher/
//   mesh_union         components united as meshes               mesher/
//   composite          re-mesh across virtual curves             mesher/
//   quality            quality, target sizes, warnings           mesher/
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "app/pipeline.h"

namespace sizemesh {

struct Stage {
  using Step = std::function<void(RunResult&, const RunOptions&, const WarningSink&)>;
  std::string name;
  Step step;
};
using Stages = std::vector<Stage>;

// Paper 3: load to estimate.
Stages sizing_stages();
// Paper 4: size_query to quality.
Stages meshing_stages();
// Both, in order.
Stages all_stages();

// The list cut after the stage `last`, started at `first`, with the stage
// `name` done by `step` instead, or without it. Throw Error on a name the
// list does not have.
Stages until(Stages stages, const std::string& last);
Stages from(Stages stages, const std::string& first);
Stages replaced(Stages stages, const std::string& name, Stage::Step step);
Stages without(Stages stages, const std::string& name);

// A run's context before its first stage: the options' sizing parameters
// with the config applied (the config file is read here).
std::unique_ptr<RunResult> start_run(const RunOptions& o);

// Runs the stages in order, each timed under its name.
void run_stages(RunResult& r, const RunOptions& o, const WarningSink& warn, const Stages& stages);

}  // namespace sizemesh
