#include "mesher/optimise.h"

#include <cstdint>
#include <unordered_map>

#include "mesher/geometry2d.h"

namespace sizemesh {
namespace {

constexpr double kCosMin = 0.5;  // triangle normal against the surface normal

uint64_t code(int a, int b) { return (uint64_t(uint32_t(a)) << 32) | uint32_t(b); }

// Shape in space of (a, b, c) at the given corner samples; -1 when the triangle
// is folded in uv or turned away from the surface.
double shape(const FaceMesh& fm, const Vec2& ua, const Vec2& ub, const Vec2& uc, const SurfaceSample& sa,
             const SurfaceSample& sb, const SurfaceSample& sc) {
  const double o = orient(ua, ub, uc);
  const double scale = (ub - ua).norm() * ((uc - ua).norm() + (uc - ub).norm());
  if (!(o > 1e-10 * scale)) return -1;
  const Vec3 nt = (sb.p - sa.p).cross(sc.p - sa.p);
  const double lt = nt.norm();
  if (!(lt > 0)) return -1;
  for (const Vec3* n : {&sa.n, &sb.n, &sc.n})  // zero on poles
    if (n->squaredNorm() > 0 && nt.dot(*n) < kCosMin * lt) return -1;
  return triangle_quality(sa.p, sb.p, sc.p);
}

double shape(const FaceMesh& fm, const std::array<int, 3>& t) {
  return shape(fm, fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]], fm.s[t[0]], fm.s[t[1]], fm.s[t[2]]);
}

// One sweep of diagonal swaps that raise the worse shape of the two triangles.
int swap_sweep(FaceMesh& fm) {
  std::unordered_map<uint64_t, int> edge_tri;
  edge_tri.reserve(fm.tris.size() * 3);
  for (int t = 0; t < static_cast<int>(fm.tris.size()); ++t)
    for (int k = 0; k < 3; ++k) edge_tri[code(fm.tris[t][k], fm.tris[t][(k + 1) % 3])] = t;
  std::vector<char> touched(fm.tris.size(), 0), pole(fm.tris.size(), 0);
  for (size_t t = 0; t < fm.tris.size(); ++t) pole[t] = fm.pole_triangle(fm.tris[t]);
  int swaps = 0;
  for (int t1 = 0; t1 < static_cast<int>(fm.tris.size()); ++t1) {
    for (int k = 0; k < 3 && !touched[t1] && !pole[t1]; ++k) {
      const int a = fm.tris[t1][k], b = fm.tris[t1][(k + 1) % 3], c = fm.tris[t1][(k + 2) % 3];
      auto it = edge_tri.find(code(b, a));
      if (it == edge_tri.end()) continue;
      const int t2 = it->second;
      if (touched[t2] || pole[t2]) continue;
      int d = -1;
      for (int j = 0; j < 3; ++j)
        if (fm.tris[t2][j] != a && fm.tris[t2][j] != b) d = fm.tris[t2][j];
      if (d < 0 || d == c || edge_tri.count(code(c, d)) || edge_tri.count(code(d, c))) continue;
      const std::array<int, 3> n1{a, d, c}, n2{d, b, c};
      if (fm.pole_triangle(n1) || fm.pole_triangle(n2)) continue;
      const double q_old = std::min(shape(fm, fm.tris[t1]), shape(fm, fm.tris[t2]));
      const double q_new = std::min(shape(fm, n1), shape(fm, n2));
      if (!(q_new > q_old + 1e-6)) continue;
      fm.tris[t1] = n1;
      fm.tris[t2] = n2;
      touched[t1] = touched[t2] = 1;
      ++swaps;
    }
  }
  return swaps;
}

// One sweep of smoothing: each inner node moves towards the mean of its
// neighbours in space (one Gauss-Newton step in uv), kept only if the worst
// shape around it does not get worse.
int smooth_sweep(FaceMesh& fm, FaceSurface& fs) {
  const int n = fm.num_nodes();
  std::vector<std::vector<int>> node_tris(n);
  for (int t = 0; t < static_cast<int>(fm.tris.size()); ++t)
    for (int k = 0; k < 3; ++k) node_tris[fm.tris[t][k]].push_back(t);
  int moved = 0;
  for (int i = 0; i < n; ++i) {
    if (fm.boundary(i) || node_tris[i].empty()) continue;
    Vec3 target = Vec3::Zero();
    int cnt = 0;
    double old_q = 2;
    for (int t : node_tris[i]) {
      for (int v : fm.tris[t])
        if (v != i) {
          target += fm.s[v].p;
          ++cnt;
        }
      if (!fm.pole_triangle(fm.tris[t])) old_q = std::min(old_q, shape(fm, fm.tris[t]));
    }
    target /= cnt;
    const SurfaceSample& si = fm.s[i];
    Eigen::Matrix<double, 3, 2> J;
    J.col(0) = si.du;
    J.col(1) = si.dv;
    const Eigen::Matrix2d JtJ = J.transpose() * J;
    if (!(std::abs(JtJ.determinant()) > 1e-300)) continue;
    const Vec2 step = JtJ.ldlt().solve(J.transpose() * (target - si.p));
    if (!std::isfinite(step.x()) || !std::isfinite(step.y())) continue;
    for (double f : {1.0, 0.5}) {
      const Vec2 uv = fm.uv[i] + f * step;
      const SurfaceSample s = fs.eval(uv);
      double new_q = 2;
      bool ok = true;
      for (int t : node_tris[i]) {
        const auto& tr = fm.tris[t];
        Vec2 u[3];
        const SurfaceSample* p[3];
        for (int k = 0; k < 3; ++k) {
          u[k] = tr[k] == i ? uv : fm.uv[tr[k]];
          p[k] = tr[k] == i ? &s : &fm.s[tr[k]];
        }
        if (fm.pole_triangle(tr)) {
          if (!(orient(u[0], u[1], u[2]) > 0)) ok = false;
          continue;
        }
        const double q = shape(fm, u[0], u[1], u[2], *p[0], *p[1], *p[2]);
        if (q < 0) ok = false;
        new_q = std::min(new_q, q);
        if (!ok) break;
      }
      if (!ok || new_q < old_q) continue;
      fm.uv[i] = uv;
      fm.s[i] = s;
      ++moved;
      break;
    }
  }
  return moved;
}

}  // namespace

void optimise(FaceMesh& fm, FaceSurface& fs, int passes) {
  for (int p = 0; p < passes; ++p) {
    for (int k = 0; k < 4 && swap_sweep(fm) > 0; ++k) {
    }
    smooth_sweep(fm, fs);
  }
  if (passes > 0)
    for (int k = 0; k < 4 && swap_sweep(fm) > 0; ++k) {
    }
}

}  // namespace sizemesh
