// Surface mesher benchmark (paper 4.1): per shared model, time, triangles,
// triangles per second and quality counts, with one thread against all threads
// in the same process, for a uniform size h = diagonal / N (--div, default 40)
// and for the automatic size map (paper 3: the command's stages up to the size
// query, then its meshing stage). Prints only.
//
// Usage: bench_mesher [model-file ...] [--div N] [--no-size-map]
//        (default: every shared model)
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <cstdio>
#include <cstring>
#include <unistd.h>
#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "app/stages.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "tests/stage_runs.h"

using namespace sizemesh;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Meshes with `threads` threads (0: all).
using Mesher = std::function<SurfaceMesh(int threads)>;

// Meshes once with one thread and once with all, and prints one row.
// Returns the triangles per second with one thread.
double run(const std::string& name, const char* size_name, const Model& model, const SizeField& h, const Mesher& mesh) {
  double cad_area = 0;
  for (int f = 1; f <= model.num_faces(); ++f) cad_area += model.face_area(f);
  auto t0 = std::chrono::steady_clock::now();
  const SurfaceMesh m1 = mesh(1);
  const double s1 = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const SurfaceMesh m = mesh(0);
  const double sn = seconds_since(t0);
  const MeshQuality q = mesh_quality(m, model, h);
  std::printf("%-32s %-9s %6d %9d %8.3f %8.3f %10.0f %6.2f %6d %6d %5d %5d %5d %9.5f %6.3f %5zu %5d\n",
              name.c_str(), size_name, model.num_faces(), q.triangles, s1, sn, q.triangles / sn, s1 / sn,
              q.below_12, q.below_24, q.boundary_edges, q.nonmanifold_edges, q.inverted,
              (q.area - cad_area) / cad_area, q.size_conformity, m.failures.size(), m.stats.fronts_3d);
  std::printf("    stages: curves %.3fs, faces %.3fs (front %.3fs + optimise %.3fs summed), %lld size queries, "
              "worst angle %.2f deg; share below 12 deg %.4f%%, below 24 deg %.3f%%; faces retried %d "
              "(last resort %d)\n",
              m.stats.seconds_curves, m.stats.seconds_faces, m.stats.seconds_front, m.stats.seconds_optimise,
              m.stats.size_queries, q.worst_angle, 100.0 * q.below_12 / std::max(1, q.triangles),
              100.0 * q.below_24 / std::max(1, q.triangles), m.stats.faces_retried, m.stats.faces_relaxed);
  std::printf("    min-angle histogram (6 deg bins):");
  for (int c : q.histogram) std::printf(" %d", c);
  std::printf("\n");
  for (const auto& f : m.failures) std::printf("    face %d failed: %s\n", f.face, f.reason.c_str());
  if (m1.tris != m.tris || m1.xyz != m.xyz) std::printf("    WARNING: the mesh differs between 1 and all threads\n");
  std::fflush(stdout);
  return s1 > 0 ? m1.tris.size() / s1 : 0;
}

// The meshing stage's triangles per second of `binary` on one thread, from
// its report; 0 when it gives none.
double command_rate(const std::string& binary, const std::string& model, std::string& note) {
  const std::string dir = "/tmp/bench_mesher_" + std::to_string(::getpid());
  std::system(("mkdir -p " + dir).c_str());
  const std::string cmd = "'" + binary + "' '" + model + "' --threads 1 -q -o " + dir + "/m.vtu --report " + dir +
                          "/r.json > /dev/null 2>&1";
  std::remove((dir + "/r.json").c_str());
  std::system(cmd.c_str());
  std::ifstream in(dir + "/r.json");
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    const double seconds = j.at("seconds").at("meshing").get<double>();
    const double tris = j.at("mesh").at("triangles").get<double>();
    char line[120];
    std::snprintf(line, sizeof line, "%.0f tris in %.3f s", tris, seconds);
    note = line;
    return seconds > 0 ? tris / seconds : 0;
  } catch (const std::exception&) {
    note = "no report with seconds.meshing";
    return 0;
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  double div = 40;
  bool size_map = true;
  std::string baseline;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--div") && i + 1 < argc) div = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--baseline") && i + 1 < argc) baseline = argv[++i];
    else if (!std::strcmp(argv[i], "--no-size-map")) size_map = false;
    else files.push_back(argv[i]);
  }
  std::string self_dir = argv[0];
  self_dir = self_dir.find('/') == std::string::npos ? "." : self_dir.substr(0, self_dir.find_last_of('/'));
  if (files.empty())
    for (const auto& m : sizemesh::test::shared_models())  // one list for tests and benches
      files.push_back(std::string(SIZEMESH_MODELS_DIR) + "/" + m.file);
  std::printf("%-32s %-9s %6s %9s %8s %8s %10s %6s %6s %6s %5s %5s %5s %9s %6s %5s %5s\n", "model", "size",
              "faces", "tris", "t1[s]", "tN[s]", "tris/s(N)", "t1/tN", "<12", "<24", "bnd", "nonm", "inv",
              "area_err", "conf", "fail", "3d");
  for (const std::string& path : files) {
    const std::string name = path.substr(path.find_last_of('/') + 1);
    try {
      // The command's stages (app/stages.h) up to the size query: the model,
      // and the size map with its accuracy rules and per-face estimate.
      RunOptions o;
      o.input = path;
      o.verbose = false;
      const std::unique_ptr<RunResult> r = start_run(o);
      const auto t0 = std::chrono::steady_clock::now();
      run_stages(*r, o, sizemesh::test::quiet(), until(all_stages(), "size_query"));
      const double sized = seconds_since(t0);
      const Model& model = *r->model;
      const UniformSize uniform(model.info().diagonal() / div);
      run(name, "uniform", model, uniform, [&](int threads) {
        MeshOptions mo;
        mo.threads = threads;
        return mesh_surface(model, uniform, mo);
      });
      if (!size_map) continue;
      std::printf("    size map built in %.3f s\n", sized);
      // The meshing stage itself, as the command runs it, with 1 and all threads.
      run(name, "size map", model, *r->query, [&](int threads) {
        RunOptions with = o;
        with.meshing.threads = threads;
        run_stages(*r, with, sizemesh::test::quiet(), until(from(all_stages(), "meshing"), "meshing"));
        return r->mesh;
      });
      if (!r->report.evaluations.empty() && r->report.evaluations.back().first == "meshing" && !r->mesh.tris.empty())
        std::printf("    surface evaluations per triangle, meshing stage: %.1f (face setup %.1f, front %.1f, "
                    "optimisation %.1f; the rest curves and assembly)\n",
                    double(r->report.evaluations.back().second) / r->mesh.tris.size(),
                    double(r->mesh.stats.evaluations_setup) / r->mesh.tris.size(),
                    double(r->mesh.stats.evaluations_front) / r->mesh.tris.size(),
                    double(r->mesh.stats.evaluations_optimise) / r->mesh.tris.size());
      if (!baseline.empty()) {
        // Both as commands, one after the other: the same work, the same machine state.
        std::string mine_note, base_note;
        const double mine = command_rate(self_dir + "/../sizemesh", path, mine_note);
        const double base = command_rate(baseline, path, base_note);
        std::printf("    meshing stage, 1 thread: this build %s (%.0f tris/s), baseline %s (%.0f tris/s): ratio %.2f\n",
                    mine_note.c_str(), mine, base_note.c_str(), base, base > 0 ? mine / base : 0.0);
      }
    } catch (const std::exception& e) {
      std::printf("%-32s error: %s\n", name.c_str(), e.what());
    }
    std::fflush(stdout);
  }
  return 0;
}
