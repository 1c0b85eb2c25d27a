// Benchmark of the size query (paper 4.2) on the shared models, one core.
//
// For each model: a non-constant size field on the background vertices, then
// coherent query streams like an advancing-front mesher's: random walks inside
// a face whose steps are about the local size h in xyz (0.5 h to 1.5 h), mapped
// to uv by the surface derivatives, each query hinted by the previous answer. Measured in the same run: walk-through queries/second (locate without
// counters, at() with its per-thread counters, and with no hint at all), mean
// and max triangles visited, fallbacks, and brute-force queries/second on a
// slice of the same stream, with the ratio. Prints only; never fails on timing.
//
// Usage: bench_size_query [queries per model, default 1000000] [model files...]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "background/background_mesh.h"
#include "cad/model.h"
#include "sizing/size_query.h"

using namespace sizemesh;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// A non-constant size field on the scale of the background mesh: at each vertex
// the mean length of its background edges, times a smooth factor in [0.5, 1.5]
// of the position (the paper's initial sizes follow the same curvature and
// deflection the tessellation resolves).
std::vector<double> local_sizes(const BackgroundMesh& bg) {
  Vec3 lo = bg.xyz[0], hi = lo;
  for (const Vec3& p : bg.xyz) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double D = (hi - lo).norm();
  std::vector<double> sum(bg.xyz.size(), 0.0);
  std::vector<int> cnt(bg.xyz.size(), 0);
  for (const auto& e : bg.edges) {
    const double l = (bg.xyz[e[0]] - bg.xyz[e[1]]).norm();
    for (int v : e) {
      sum[v] += l;
      ++cnt[v];
    }
  }
  std::vector<double> h(bg.xyz.size());
  for (size_t i = 0; i < h.size(); ++i) {
    const Vec3 q = (bg.xyz[i] - lo) / D;
    const double base = cnt[i] && sum[i] > 0 ? sum[i] / cnt[i] : 1e-3 * D;
    h[i] = base * (1.0 + 0.5 * std::sin(7 * q.x() + 5 * q.y() + 3 * q.z()));
  }
  return h;
}

struct Query {
  int face;
  Vec2 uv;
};

// Coherent streams: random walks of 100 steps inside faces picked in proportion
// to their triangle counts; a step leaving the domain is retried in another direction.
std::vector<Query> coherent_stream(const Model& model, const BackgroundMesh& bg, const SizeQuery& query, size_t n,
                                   std::mt19937& rng) {
  std::vector<int> faces;
  std::vector<double> weight;
  for (const FacePatch& p : bg.patches)
    if (!p.tris.empty()) {
      faces.push_back(p.face);
      weight.push_back(static_cast<double>(p.tris.size()));
    }
  std::discrete_distribution<int> pick_face(weight.begin(), weight.end());
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<Query> out;
  out.reserve(n);
  while (out.size() < n) {
    const FacePatch& patch = bg.patches[faces[pick_face(rng)] - 1];
    const int nt = static_cast<int>(patch.tris.size());
    int t = static_cast<int>(rng() % nt);
    double a = U(rng), b = U(rng);
    if (a + b > 1) {
      a = 1 - a;
      b = 1 - b;
    }
    const auto& v = patch.tris[t];
    Vec2 p = (1 - a - b) * patch.uv[v[0]] + a * patch.uv[v[1]] + b * patch.uv[v[2]];
    SizeQuery::Hit hit = query.locate(patch.face, p, t);
    for (int step = 0; step < 100 && out.size() < n; ++step) {
      out.push_back({patch.face, p});
      // A step of about h in xyz, mapped to uv by the surface derivatives at p.
      const SurfaceD1 d1 = model.eval_face(patch.face, p);
      for (int attempt = 0; attempt < 8; ++attempt) {
        const double angle = 2 * M_PI * U(rng);
        const Vec2 dir(std::cos(angle), std::sin(angle));
        const double stretch = (dir.x() * d1.du + dir.y() * d1.dv).norm();  // xyz length per uv length
        if (!(stretch > 0)) continue;
        const Vec2 q = p + hit.h * (0.5 + U(rng)) / stretch * dir;
        QueryStats st;
        const SizeQuery::Hit next = query.locate(patch.face, q, hit.tri, &st);
        if (st.outside || st.fallbacks) continue;
        p = q;
        hit = next;
        break;
      }
    }
  }
  return out;
}

struct Timing {
  double qps = 0, checksum = 0;
};

// Runs the stream `repeat` times through `one(query, hint)`, hints chained.
template <class F>
Timing run(const std::vector<Query>& stream, size_t count, int repeat, F one) {
  Timing r;
  const auto t0 = Clock::now();
  for (int rep = 0; rep < repeat; ++rep) {
    int hint = -1, face = -1;
    for (size_t i = 0; i < count; ++i) {
      const Query& q = stream[i];
      if (q.face != face) {
        face = q.face;
        hint = -1;
      }
      r.checksum += one(q, hint);
    }
  }
  r.qps = static_cast<double>(count) * repeat / seconds_since(t0);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  size_t n = 1000000;
  std::vector<std::string> paths;
  for (int i = 1; i < argc; ++i) {
    char* end = nullptr;
    const long v = std::strtol(argv[i], &end, 10);
    if (end && *end == 0 && v > 0) n = static_cast<size_t>(v);
    else paths.push_back(argv[i]);
  }
  if (paths.empty()) {
    for (const auto& e : std::filesystem::directory_iterator(SIZEMESH_MODELS_DIR)) {
      const std::string ext = e.path().extension().string();
      if (ext == ".stp" || ext == ".step" || ext == ".igs" || ext == ".iges") paths.push_back(e.path().string());
    }
    std::sort(paths.begin(), paths.end());
  }
  std::printf("size query benchmark (paper 4.2), one core, %zu coherent queries per model\n", n);
  std::printf("walk: start at the nearer of hint and grid cell (default); paper: hint only; cold: no hint\n");
  std::printf("%-31s %5s | %8s %8s %5s %4s %3s %3s | %8s %5s | %8s %5s | %8s %6s | %8s\n", "model", "tris", "walk q/s",
              "at() q/s", "mean", "max", "fb", "out", "paper/s", "mean", "cold/s", "mean", "brute/s", "ratio", "xyz q/s");
  double total_walk = 0, total_brute = 0, total_q = 0, total_bq = 0;
  QueryStats all;
  for (const std::string& path : paths) {
    const std::string name = std::filesystem::path(path).filename().string();
    try {
      const Model model = load_model(path);
      const BackgroundMesh bg = build_background_mesh(model);
      SizeQuery query = size_query_for(model, bg, local_sizes(bg));
      std::mt19937 rng(2024);
      const std::vector<Query> stream = coherent_stream(model, bg, query, n, rng);
      auto hinted = [&](const Query& q, int& hint) {
        const SizeQuery::Hit hit = query.locate(q.face, q.uv, hint);
        hint = hit.tri;
        return hit.h;
      };

      // Walk-through, hinted by the previous answer, no counters.
      const Timing walk = run(stream, stream.size(), 3, hinted);
      // The SizeField entry point, with its per-thread counters.
      query.reset_stats();
      const Timing at = run(stream, stream.size(), 1, [&](const Query& q, int& hint) { return query.at(q.face, q.uv, hint); });
      const QueryStats st = query.stats();
      all.add(st);
      // As in the paper: from the hint alone.
      query.set_grid_with_hint(false);
      const Timing paper = run(stream, stream.size(), 1, hinted);
      query.reset_stats();
      run(stream, stream.size(), 1, [&](const Query& q, int& hint) { return query.at(q.face, q.uv, hint); });
      const QueryStats paper_st = query.stats();
      query.set_grid_with_hint(true);
      // No hint at all: the per-face start grid.
      QueryStats cold;
      const Timing nohint = run(stream, stream.size(), 1, [&](const Query& q, int&) {
        return query.locate(q.face, q.uv, -1, &cold).h;
      });
      // Brute force on a slice of the same stream.
      const size_t nb = std::min<size_t>(stream.size(), 20000);
      const Timing brute = run(stream, nb, 1, [&](const Query& q, int&) { return query.locate_brute_force(q.face, q.uv).h; });
      // Nearest background triangle in xyz for the same points.
      const size_t nx = std::min<size_t>(stream.size(), 50000);
      std::vector<Vec3> pts(nx);
      for (size_t i = 0; i < nx; ++i) pts[i] = model.eval_face(stream[i].face, stream[i].uv).p;
      double xyz_sum = 0;
      const auto t0 = Clock::now();
      for (const Vec3& p : pts) xyz_sum += query.at_xyz(p);
      const double xyz_qps = nx / seconds_since(t0);

      std::printf("%-31s %5d | %8.3g %8.3g %5.2f %4llu %3llu %3llu | %8.3g %5.2f | %8.3g %5.2f | %8.3g %6.1f | %8.3g\n",
                  name.c_str(), bg.num_triangles(), walk.qps, at.qps, st.mean_visited(),
                  static_cast<unsigned long long>(st.max_visited), static_cast<unsigned long long>(st.fallbacks),
                  static_cast<unsigned long long>(st.outside), paper.qps, paper_st.mean_visited(), nohint.qps,
                  cold.mean_visited(), brute.qps, walk.qps / brute.qps, xyz_qps);
      if (std::getenv("SIZEMESH_BENCH_VERBOSE"))
        std::printf("  checksums %.9g %.9g %.9g %.9g %.9g\n", walk.checksum / 3, at.checksum, paper.checksum,
                    nohint.checksum, xyz_sum);
      total_walk += stream.size() * 3 / walk.qps;
      total_q += stream.size() * 3;
      total_brute += nb / brute.qps;
      total_bq += nb;
    } catch (const std::exception& e) {
      std::printf("%-31s skipped: %s\n", name.c_str(), e.what());
    }
  }
  if (total_q > 0 && total_bq > 0)
    std::printf("all models: walk %.3g queries/s (mean visited %.2f, max %llu, fallbacks %llu), brute force %.3g "
                "queries/s, ratio %.1f\n",
                total_q / total_walk, all.mean_visited(), static_cast<unsigned long long>(all.max_visited),
                static_cast<unsigned long long>(all.fallbacks), total_bq / total_brute,
                (total_q / total_walk) / (total_bq / total_brute));
  return 0;
}
