// Sizing-stage benchmark (paper section 3): load, tessellate, classify,
// initialise, refine the background and smooth on every shared model, one
// thread (the refinement's share is shown apart: "init s" covers the sizes of
// the tessellation alone, "refine s" the rounds of splitting and re-sizing); the exact edge
// solver against lp_solve in the same run; the triangles the smoothed map asks
// for, and that count over the edge stage's alone (what the triangle stage,
// Eq. 11, costs); smoothing on a background mesh of the paper's F-16 size
// (about 47k triangles). Prints only.
//
//   ./build/bench/bench_sizing [models_dir]
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "app/stages.h"
#include "sizing/lp_smooth.h"
#include "sizing/triangle_estimate.h"
#include "tests/stage_runs.h"

using namespace sizemesh;

namespace {
double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
}  // namespace

// The wall time of a finished stage, from the run's report.
double stage_seconds(const RunResult& r, const std::string& name) {
  for (const auto& [stage, seconds] : r.report.seconds)
    if (stage == name) return seconds;
  return 0;
}

int main(int argc, char** argv) {
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  const std::string dir = argc > 1 ? argv[1] : SIZEMESH_MODELS_DIR;
  std::vector<std::string> files;  // the test models (tests/test_models.h): one list for tests and benches
  for (const auto& m : sizemesh::test::shared_models()) files.push_back(m.file);
  std::printf("%-32s %8s %8s %8s %8s %8s %8s %8s %8s %9s %9s %8s %9s %8s\n", "model", "load s", "tess s", "init s",
              "refine s", "smooth s", "total s", "tess tri", "bg tris", "edge ms", "lp ms", "lp/exact",
              "triangles", "/edge");
  for (const std::string& f : files) {
    // The command's stages (app/stages.h), stopped after the initial sizes to
    // count the tessellation's triangles, then run on to the smoothing.
    RunOptions o;
    o.input = dir + "/" + f;
    o.verbose = false;
    const std::unique_ptr<RunResult> r = start_run(o);
    run_stages(*r, o, sizemesh::test::quiet(), until(all_stages(), "initial_sizes"));
    const int tess_tris = r->bg.num_triangles();
    run_stages(*r, o, sizemesh::test::quiet(), until(from(all_stages(), "refine_background"), "smoothing"));
    const double t_load = stage_seconds(*r, "load") + stage_seconds(*r, "prepare");
    const double t_tess = stage_seconds(*r, "background"), t_init = stage_seconds(*r, "initial_sizes");
    const double t_refine = stage_seconds(*r, "refine_background"), t_smooth = stage_seconds(*r, "smoothing");
    const BackgroundMesh& bg = r->bg;
    const SizeMap& m = r->sizes;
    const Model& model = *r->model;
    std::vector<double> h = m.h_initial;
    double t = now();
    smooth_edges(bg, m.edge_log_beta, h);
    const double t_edge = now() - t;
    // What the triangle stage (Eq. 11) costs over the edge stage alone, in triangles asked for.
    const double n_edge = estimate_triangles(bg, h, {}, model.num_faces()).total;
    const double n_final = estimate_triangles(bg, m.h, {}, model.num_faces()).total;
    h = m.h_initial;
    t = now();
    smooth_edges_lp(bg, m.edge_log_beta, h);
    const double t_lp = now() - t;
    std::printf("%-32s %8.3f %8.3f %8.3f %8.3f %8.4f %8.3f %8d %8d %9.2f %9.1f %8.0f %9.0f %8.2f\n", f.c_str(), t_load, t_tess, t_init,
                t_refine, t_smooth, t_load + t_tess + t_init + t_refine + t_smooth, tess_tris, bg.num_triangles(),
                1e3 * t_edge, 1e3 * t_lp, t_lp / t_edge, n_final, n_final / n_edge);
  }
  // The paper's F-16 background mesh had 47,127 triangles: the tessellation
  // made that fine, the refinement left out (the paper has none), and the
  // smoothing stage timed.
  RunOptions o;
  o.input = dir + "/f16_openvsp.stp";
  o.verbose = false;
  o.tessellation.deflection_rel = 2.5e-4;
  o.tessellation.angle_deg = 8;
  const std::unique_ptr<RunResult> r = start_run(o);
  run_stages(*r, o, sizemesh::test::quiet(), without(until(all_stages(), "smoothing"), "refine_background"));
  const double t_smooth = stage_seconds(*r, "smoothing");
  std::printf("\nF-16, %d background triangles: smoothing (edge + triangle stages) %.1f ms in %d rounds "
              "(paper: 107 s for Eq. 12 on 47,127 triangles, ratio %.0f)\n",
              r->bg.num_triangles(), 1e3 * t_smooth, r->report.smoothing.rounds, 107.0 / t_smooth);
  return 0;
}
