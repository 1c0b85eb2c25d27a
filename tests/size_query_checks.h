// Models with wavy background sizes and random points in their patches, shared by the size query's tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "background/background_mesh.h"
#include "cad/model.h"
#include "sizing/size_query.h"

namespace sizemesh::test {

// A non-constant size per background vertex, smooth in xyz.
inline std::vector<double> wavy_sizes(const BackgroundMesh& bg) {
  Vec3 lo = bg.xyz.empty() ? Vec3::Zero() : bg.xyz[0], hi = lo;
  for (const Vec3& p : bg.xyz) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double D = std::max((hi - lo).norm(), 1e-300);
  std::vector<double> h(bg.xyz.size());
  for (size_t i = 0; i < h.size(); ++i) {
    const Vec3 q = (bg.xyz[i] - lo) / D;
    h[i] = D * (0.01 + 0.02 * std::abs(std::sin(7 * q.x())) + 0.01 * std::abs(std::cos(5 * q.y() + 3 * q.z())));
  }
  return h;
}

// A model's background mesh, wavy sizes on it and its faces' periods.
struct Case {
  std::string name;
  BackgroundMesh bg;
  std::vector<double> h, period_u, period_v;
};

inline Case make_case(const std::string& name, const Model& model) {
  Case c;
  c.name = name;
  c.bg = build_background_mesh(model);
  c.h = wavy_sizes(c.bg);
  for (int f = 1; f <= model.num_faces(); ++f) {
    c.period_u.push_back(model.face_period_u(f));
    c.period_v.push_back(model.face_period_v(f));
  }
  return c;
}

inline double area2(const FacePatch& patch, int t) {
  const auto& v = patch.tris[t];
  const Vec2 e1 = patch.uv[v[1]] - patch.uv[v[0]], e2 = patch.uv[v[2]] - patch.uv[v[0]];
  return e1.x() * e2.y() - e1.y() * e2.x();
}

inline bool proper(const FacePatch& patch, int t) {
  const auto& v = patch.tris[t];
  const double l = std::max({(patch.uv[v[1]] - patch.uv[v[0]]).squaredNorm(), (patch.uv[v[2]] - patch.uv[v[0]]).squaredNorm(),
                             (patch.uv[v[2]] - patch.uv[v[1]]).squaredNorm()});
  return area2(patch, t) > 1e-6 * l;
}

// A random point inside triangle t of the patch (uniform barycentric).
inline Vec2 sample(const FacePatch& patch, int t, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(0, 1);
  double a = U(rng), b = U(rng);
  if (a + b > 1) {
    a = 1 - a;
    b = 1 - b;
  }
  const auto& v = patch.tris[t];
  return (1 - a - b) * patch.uv[v[0]] + a * patch.uv[v[1]] + b * patch.uv[v[2]];
}

inline bool same(const SizeQuery::Hit& a, const SizeQuery::Hit& b) {
  return a.tri == b.tri || std::abs(a.h - b.h) <= 1e-12 * std::max(std::abs(a.h), std::abs(b.h));
}

}  // namespace sizemesh::test
