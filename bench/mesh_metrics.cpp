// Measures any triangle mesh against its CAD model, the same way for every
// tool: triangles, min-angle shares below 12 and 24 degrees, and the distance
// to the CAD surface, relative to the bounding-box diagonal, of triangle
// centroids and of edge midpoints (max and mean over both, and over centroids
// alone). Midpoints catch a chord cutting a curved edge or rim, which no
// centroid sees. Reads Gmsh .msh ASCII files, versions 2.2 and 4.1.
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
#include <unordered_set>
#include <vector>

#include "background/background_mesh.h"
#include "cad/model.h"
#include "core/triangle_bvh.h"

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

// Candidate faces from the background triangles nearest to the point (within
// the tessellation tolerance of the nearest), then Newton on each face from
// the uv of the closest point on that triangle.
class SurfaceDistance {
 public:
  SurfaceDistance(const Model& model, const BackgroundMesh& bg, double slack)
      : model_(model), bg_(bg), bvh_(bg.xyz, bg.tris), slack_(slack) {
    local_.resize(bg.tris.size(), {-1, -1});
    for (const FacePatch& patch : bg.patches)
      for (size_t t = 0; t < patch.tris.size(); ++t)
        if (patch.global_tri[t] >= 0) local_[patch.global_tri[t]] = {patch.face, static_cast<int>(t)};
  }
  double operator()(const Vec3& p) const {
    double best = INFINITY;
    for (const auto& [t, d] : bvh_.nearest(p, slack_)) {
      best = std::min(best, d);
      const auto [f, lt] = local_[t];
      if (f < 0) continue;
      const FacePatch& patch = bg_.patches[f - 1];
      const auto& tr = patch.tris[lt];
      const Vec3 w = TriangleBVH::closest_barycentric(p, bg_.xyz[patch.vertex[tr[0]]], bg_.xyz[patch.vertex[tr[1]]],
                                                      bg_.xyz[patch.vertex[tr[2]]]);
      best = std::min(best, project(f, p, w[0] * patch.uv[tr[0]] + w[1] * patch.uv[tr[1]] + w[2] * patch.uv[tr[2]]));
    }
    return best;
  }

 private:
  // Distance from p to face f's surface: Newton from uv, kept inside the
  // face's parameter box (outside it a B-spline is extrapolated or undefined)
  // except along periodic directions.
  double project(int f, const Vec3& p, Vec2 uv) const {
    const UVBox box = model_.face_uv_bounds(f);
    const bool periodic[2] = {model_.face_period_u(f) > 0, model_.face_period_v(f) > 0};
    double d = INFINITY;
    for (int it = 0; it < 20; ++it) {
      const SurfaceD1 s = model_.eval_face(f, uv);
      const Vec3 r = p - s.p;
      d = std::min(d, r.norm());
      Eigen::Matrix2d a;
      a << s.du.dot(s.du), s.du.dot(s.dv), s.du.dot(s.dv), s.dv.dot(s.dv);
      if (!(std::abs(a.determinant()) > 1e-300)) break;
      const Vec2 step = a.inverse() * Vec2(s.du.dot(r), s.dv.dot(r));
      Vec2 next = uv + step;
      for (int k = 0; k < 2; ++k)
        if (!periodic[k]) next[k] = std::clamp(next[k], box.lo[k], box.hi[k]);
      if ((next - uv).norm() <= 1e-14 * (1 + (box.hi - box.lo).norm())) break;
      uv = next;
    }
    return d;
  }

  const Model& model_;
  const BackgroundMesh& bg_;
  TriangleBVH bvh_;
  double slack_;
  std::vector<std::pair<int, int>> local_;  // global triangle -> (face, local triangle)
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
    SurfaceDistance distance(model, bg, 2 * fine.deflection_rel * model.info().diagonal());
    const double diag = model.info().diagonal();
    int below12 = 0, below24 = 0;
    double worst = 180, area = 0;
    struct Extreme {
      double max = 0, sum = 0;
      size_t n = 0;
      Vec3 at = Vec3::Zero();
      void add(double d, const Vec3& p) {
        if (d > max) max = d, at = p;
        sum += d;
        ++n;
      }
      double mean() const { return n ? sum / n : 0.0; }
    } centroids, all;
    std::unordered_set<uint64_t> edges;  // each edge's midpoint once
    for (const auto& t : m.tris) {
      const Vec3 &a = m.xyz[t[0]], &b = m.xyz[t[1]], &c = m.xyz[t[2]];
      const double ang = min_angle_deg(a, b, c);
      below12 += ang < 12;
      below24 += ang < 24;
      worst = std::min(worst, ang);
      area += 0.5 * (b - a).cross(c - a).norm();
      const Vec3 g = (a + b + c) / 3.0;
      const double d = distance(g) / diag;
      centroids.add(d, g);
      all.add(d, g);
      for (int k = 0; k < 3; ++k) {
        const int i = t[k], j = t[(k + 1) % 3];
        if (!edges.insert(edge_key(i, j)).second) continue;
        const Vec3 mid = 0.5 * (m.xyz[i] + m.xyz[j]);
        all.add(distance(mid) / diag, mid);
      }
    }
    const double n = std::max<size_t>(1, m.tris.size());
    std::printf("{\"triangles\": %zu, \"nodes\": %zu, \"below_12\": %d, \"below_24\": %d, \"share_below_12\": %.6g, "
                "\"share_below_24\": %.6g, \"worst_angle\": %.4g, \"max_distance_rel\": %.4g, "
                "\"mean_distance_rel\": %.4g, \"max_distance_at\": [%.6g, %.6g, %.6g], "
                "\"max_centroid_distance_rel\": %.4g, \"mean_centroid_distance_rel\": %.4g, \"area\": %.10g}\n",
                m.tris.size(), m.xyz.size(), below12, below24, below12 / n, below24 / n, worst, all.max, all.mean(),
                all.at.x(), all.at.y(), all.at.z(), centroids.max, centroids.mean(), area);
  } catch (const std::exception& e) {
    std::cerr << "mesh_metrics: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
