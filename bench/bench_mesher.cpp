// Surface mesher benchmark (paper 4.1): per shared model, time, triangles,
// triangles per second and quality counts, with one thread against all threads
// in the same process, for a uniform size h = diagonal / N (--div, default 40)
// and for the automatic size map (paper 3, SizeQuery). Prints only.
//
// Usage: bench_mesher [model-file ...] [--div N] [--no-size-map]
//        (default: every shared model)
#include <chrono>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <string>
#include <vector>

#include "geometry/background_mesh.h"
#include "geometry/model.h"
#include "mesher/mesh_surface.h"
#include "mesher/quality.h"
#include "sizing/refine_background.h"
#include "sizing/size_query.h"
#include "sizing/smooth.h"
#include "tests/test_models.h"

using namespace sizemesh;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Meshes once with one thread and once with all, and prints one row.
void run(const std::string& name, const char* size_name, const Model& model, const SizeFunction& h) {
  double cad_area = 0;
  for (int f = 1; f <= model.num_faces(); ++f) cad_area += model.face_area(f);
  MeshOptions o1;
  o1.threads = 1;
  auto t0 = std::chrono::steady_clock::now();
  const SurfaceMesh m1 = mesh_surface(model, h, o1);
  const double s1 = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const SurfaceMesh m = mesh_surface(model, h, {});
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
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  double div = 40;
  bool size_map = true;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--div") && i + 1 < argc) div = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--no-size-map")) size_map = false;
    else files.push_back(argv[i]);
  }
  if (files.empty())
    for (const auto& m : sizemesh::test::shared_models())  // one list for tests and benches
      files.push_back(std::string(SIZEMESH_MODELS_DIR) + "/" + m.file);
  std::printf("%-32s %-9s %6s %9s %8s %8s %10s %6s %6s %6s %5s %5s %5s %9s %6s %5s %5s\n", "model", "size",
              "faces", "tris", "t1[s]", "tN[s]", "tris/s(N)", "t1/tN", "<12", "<24", "bnd", "nonm", "inv",
              "area_err", "conf", "fail", "3d");
  for (const std::string& path : files) {
    const std::string name = path.substr(path.find_last_of('/') + 1);
    try {
      const Model model = load_model(path);
      const double diag = model.info().diagonal();
      const UniformSize uniform(diag / div);
      run(name, "uniform", model, uniform);
      if (!size_map) continue;
      const auto t0 = std::chrono::steady_clock::now();
      BackgroundMesh bg = build_background_mesh(model);
      SizeMap map = refine_background(model, bg, SizingParams{}, diag);  // as the pipeline does
      smooth(bg, map);
      const SizeQuery query = size_query_for(model, bg, map.h);
      std::printf("    size map built in %.3f s\n",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      run(name, "size map", model, query);
    } catch (const std::exception& e) {
      std::printf("%-32s error: %s\n", name.c_str(), e.what());
    }
    std::fflush(stdout);
  }
  return 0;
}
