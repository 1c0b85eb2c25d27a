// Measures any triangle mesh against its CAD model, the same way for every
// tool: triangles, min-angle shares below 12 and 24 degrees, and the distance
// of triangle centroids to the CAD surface relative to the bounding-box
// diagonal (max and mean). Reads Gmsh .msh ASCII files, versions 2.2 and 4.1.
//
//   ./build/bench/mesh_metrics MODEL MESH.msh     prints one JSON object
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "geometry/background_mesh.h"
#include "geometry/model.h"

using namespace sizemesh;

namespace {

struct TriMesh {
  std::vector<Vec3> xyz;
  std::vector<std::array<int, 3>> tris;
};

TriMesh read_msh(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot read '" + path + "'");
  TriMesh m;
  std::unordered_map<long, int> index;
  std::string line, version = "2.2";
  while (std::getline(in, line)) {
    if (line == "$MeshFormat") {
      in >> version;
      std::getline(in, line);
    } else if (line == "$Nodes") {
      if (version[0] == '4') {
        long blocks, n, lo, hi;
        in >> blocks >> n >> lo >> hi;
        for (long b = 0; b < blocks; ++b) {
          int dim, tag, param;
          long count;
          in >> dim >> tag >> param >> count;
          std::vector<long> tags(count);
          for (auto& t : tags) in >> t;
          for (long i = 0; i < count; ++i) {
            Vec3 p;
            in >> p.x() >> p.y() >> p.z();
            if (param) {  // parametric coordinates follow
              double skip;
              for (int k = 0; k < dim; ++k) in >> skip;
            }
            index[tags[i]] = static_cast<int>(m.xyz.size());
            m.xyz.push_back(p);
          }
        }
      } else {
        long n;
        in >> n;
        for (long i = 0; i < n; ++i) {
          long id;
          Vec3 p;
          in >> id >> p.x() >> p.y() >> p.z();
          index[id] = static_cast<int>(m.xyz.size());
          m.xyz.push_back(p);
        }
      }
    } else if (line == "$Elements") {
      if (version[0] == '4') {
        long blocks, n, lo, hi;
        in >> blocks >> n >> lo >> hi;
        for (long b = 0; b < blocks; ++b) {
          int dim, tag, type;
          long count;
          in >> dim >> tag >> type >> count;
          std::getline(in, line);
          for (long i = 0; i < count; ++i) {
            std::getline(in, line);
            if (type != 2) continue;
            std::istringstream s(line);
            long id, a, bb, c;
            s >> id >> a >> bb >> c;
            m.tris.push_back({index.at(a), index.at(bb), index.at(c)});
          }
        }
      } else {
        long n;
        in >> n;
        std::getline(in, line);
        for (long i = 0; i < n; ++i) {
          std::getline(in, line);
          std::istringstream s(line);
          long id, ntags;
          int type;
          s >> id >> type >> ntags;
          for (long k = 0; k < ntags; ++k) s >> id;
          if (type != 2) continue;
          long a, bb, c;
          s >> a >> bb >> c;
          m.tris.push_back({index.at(a), index.at(bb), index.at(c)});
        }
      }
    }
  }
  return m;
}

double min_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto ang = [](const Vec3& u, const Vec3& v) {
    return std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / M_PI;
  };
  return std::min({ang(b - a, c - a), ang(a - b, c - b), ang(a - c, b - c)});
}

// Nearest background vertex by a uniform grid, then Newton projection onto
// each face that vertex lies on, from its uv there.
class SurfaceDistance {
 public:
  SurfaceDistance(const Model& model, const BackgroundMesh& bg) : model_(model), bg_(bg) {
    Eigen::AlignedBox3d box;
    for (const Vec3& p : bg.xyz) box.extend(p);
    lo_ = box.min();
    const double n = std::cbrt(std::max<double>(1, bg.num_vertices()));
    cell_ = std::max(box.sizes().maxCoeff() / n, 1e-12);
    for (int v = 0; v < bg.num_vertices(); ++v) grid_[key(cell_of(bg.xyz[v]))].push_back(v);
  }
  // Faces of every background vertex within 3x the nearest one's distance: a
  // planar face has background vertices only on its rim, so the nearest vertex
  // may well lie on another face.
  double operator()(const Vec3& p) const {
    std::vector<int> near = nearby(p);
    double best = INFINITY;
    std::vector<int> tried;
    for (int v : near) {
      best = std::min(best, (bg_.xyz[v] - p).norm());
      for (int u = bg_.use_start[v]; u < bg_.use_start[v + 1]; ++u) {
        const int f = bg_.use_face[u];
        if (std::find(tried.begin(), tried.end(), f) != tried.end()) continue;
        tried.push_back(f);
        Vec2 uv = bg_.patches[f - 1].uv[bg_.use_local[u]];
        if (model_.project_to_face(f, p, uv)) best = std::min(best, (model_.eval_face(f, uv).p - p).norm());
      }
    }
    return best;
  }

 private:
  Eigen::Vector3i cell_of(const Vec3& p) const { return ((p - lo_) / cell_).array().floor().cast<int>(); }
  static long key(const Eigen::Vector3i& c) { return (long(c.x()) * 73856093) ^ (long(c.y()) * 19349663) ^ (long(c.z()) * 83492791); }
  std::vector<int> nearby(const Vec3& p) const {
    const Eigen::Vector3i c = cell_of(p);
    double best_d = INFINITY;
    std::vector<std::pair<double, int>> found;
    for (int r = 0; r < 1000; ++r) {
      for (int i = -r; i <= r; ++i)
        for (int j = -r; j <= r; ++j)
          for (int k = -r; k <= r; ++k) {
            if (std::max({std::abs(i), std::abs(j), std::abs(k)}) != r) continue;
            auto it = grid_.find(key(c + Eigen::Vector3i(i, j, k)));
            if (it == grid_.end()) continue;
            for (int v : it->second) {
              const double d = (bg_.xyz[v] - p).norm();
              found.emplace_back(d, v);
              best_d = std::min(best_d, d);
            }
          }
      if (3 * best_d < r * cell_) break;  // nothing in an outer ring is within 3x the nearest
    }
    std::vector<int> out;
    for (const auto& [d, v] : found)
      if (d <= 3 * best_d) out.push_back(v);
    return out;
  }
  const Model& model_;
  const BackgroundMesh& bg_;
  Vec3 lo_;
  double cell_;
  std::unordered_map<long, std::vector<int>> grid_;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: mesh_metrics MODEL MESH.msh\n";
    return 2;
  }
  try {
    Model model = load_model(argv[1]);
    BackgroundOptions fine;
    fine.deflection_rel = 2e-4;
    BackgroundMesh bg = build_background_mesh(model, fine);
    TriMesh m = read_msh(argv[2]);
    // A tool that converted the model to other units (Netgen reads in mm) is
    // scaled back: the ratio of diagonals snapped to a unit conversion factor.
    {
      Eigen::AlignedBox3d box;
      for (const Vec3& p : m.xyz) box.extend(p);
      const double ratio = model.info().diagonal() / box.diagonal().norm();
      double best = 1;
      for (double f : {1.0, 1e-3, 1e3, 1e-2, 1e2, 1 / 304.8, 304.8, 1 / 25.4, 25.4})
        if (std::abs(std::log(ratio / f)) < std::abs(std::log(ratio / best))) best = f;
      for (Vec3& p : m.xyz) p *= best;
    }
    SurfaceDistance distance(model, bg);
    const double diag = model.info().diagonal();
    int below12 = 0, below24 = 0;
    double worst = 180, dmax = 0, dsum = 0, area = 0;
    for (const auto& t : m.tris) {
      const Vec3 &a = m.xyz[t[0]], &b = m.xyz[t[1]], &c = m.xyz[t[2]];
      const double ang = min_angle_deg(a, b, c);
      below12 += ang < 12;
      below24 += ang < 24;
      worst = std::min(worst, ang);
      area += 0.5 * (b - a).cross(c - a).norm();
      const double d = distance((a + b + c) / 3.0) / diag;
      dmax = std::max(dmax, d);
      dsum += d;
    }
    const double n = std::max<size_t>(1, m.tris.size());
    std::printf("{\"triangles\": %zu, \"nodes\": %zu, \"below_12\": %d, \"below_24\": %d, \"share_below_12\": %.6g, "
                "\"share_below_24\": %.6g, \"worst_angle\": %.4g, \"max_centroid_distance_rel\": %.4g, "
                "\"mean_centroid_distance_rel\": %.4g, \"area\": %.10g}\n",
                m.tris.size(), m.xyz.size(), below12, below24, below12 / n, below24 / n, worst, dmax, dsum / n, area);
  } catch (const std::exception& e) {
    std::cerr << "mesh_metrics: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
