#include "mesher/ops/swap.h"

#include <algorithm>

#include "mesher/ops/local_mesh.h"

namespace sizemesh::ops {
namespace {

constexpr double kSwapBelow = 0.8;  // only triangles worse than this look for a better diagonal

}  // namespace

SwapCheck check_swap(const FaceMesh& fm, const FaceSurface& fs, const std::vector<std::array<int, 3>>& nbr,
                     const std::vector<double>& q, int t1, int k) {
  const int t2 = nbr[t1][k];
  if (t2 < 0 || fm.pole_triangle(fm.tris[t2])) return {};
  const auto T1 = fm.tris[t1], T2 = fm.tris[t2];
  const int a = T1[k], b = T1[(k + 1) % 3], c = T1[(k + 2) % 3];
  const int j = reversed_edge(T2, a, b);
  if (j < 0) return {};
  const int d = T2[(j + 2) % 3];
  if (d == c) return {};
  const std::array<int, 3> n1{c, a, d}, n2{d, b, c};
  if (fm.pole_triangle(n1) || fm.pole_triangle(n2)) return {};
  const double q_old = std::min(q[t1], q[t2]);
  const double q1 = shape(fm, fs, n1), q2 = shape(fm, fs, n2);
  if (!(std::min(q1, q2) > q_old + 1e-6)) return {};
  return {true, t2, j, n1, n2, q1, q2};
}

void apply_swap(FaceMesh& fm, std::vector<std::array<int, 3>>& nbr, std::vector<double>& q, int t1, int k,
                const SwapCheck& c) {
  const int t2 = c.t2, j = c.j;
  q[t1] = c.q1;
  q[t2] = c.q2;
  const int o_ca = nbr[t1][(k + 2) % 3], o_bc = nbr[t1][(k + 1) % 3];
  const int o_ad = nbr[t2][(j + 1) % 3], o_db = nbr[t2][(j + 2) % 3];
  fm.tris[t1] = c.n1;  // edges c-a, a-d, d-c
  fm.tris[t2] = c.n2;  // edges d-b, b-c, c-d
  nbr[t1] = {o_ca, o_ad, t2};
  nbr[t2] = {o_db, o_bc, t1};
  repoint(nbr, o_ad, t2, t1);
  repoint(nbr, o_bc, t1, t2);
}

int swap_sweep(FaceMesh& fm, const FaceSurface& fs, std::vector<std::array<int, 3>>& nbr) {
  int swaps = 0;
  const int n = static_cast<int>(fm.tris.size());
  std::vector<double> q(n);
  for (int t = 0; t < n; ++t) q[t] = fm.pole_triangle(fm.tris[t]) ? 2.0 : shape(fm, fs, fm.tris[t]);
  for (int t1 = 0; t1 < n; ++t1) {
    if (fm.pole_triangle(fm.tris[t1]) || q[t1] > kSwapBelow) continue;
    for (int k = 0; k < 3; ++k) {
      const SwapCheck c = check_swap(fm, fs, nbr, q, t1, k);
      if (!c.ok) continue;
      apply_swap(fm, nbr, q, t1, k, c);
      ++swaps;
      break;  // t1 changed: move on
    }
  }
  return swaps;
}

}  // namespace sizemesh::ops
