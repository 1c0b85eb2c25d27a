#include "sizing/lp_smooth.h"

#include <lp_lib.h>

#include <memory>

namespace sizemesh {

void smooth_edges_lp(const BackgroundMesh& bg, const std::vector<double>& edge_log_beta, std::vector<double>& h) {
  const int n = bg.num_vertices();
  std::unique_ptr<lprec, void (*)(lprec*)> lp(make_lp(0, n), delete_lp);
  if (!lp) throw Error("lp_solve could not allocate the smoothing problem");
  set_verbose(lp.get(), NEUTRAL);
  set_add_rowmode(lp.get(), TRUE);
  for (size_t e = 0; e < bg.edges.size(); ++e) {
    const double w = edge_log_beta[e] * (bg.xyz[bg.edges[e][0]] - bg.xyz[bg.edges[e][1]]).norm();
    int cols[2] = {bg.edges[e][0] + 1, bg.edges[e][1] + 1};
    double plus_minus[2] = {1.0, -1.0}, minus_plus[2] = {-1.0, 1.0};
    add_constraintex(lp.get(), 2, plus_minus, cols, LE, w);
    add_constraintex(lp.get(), 2, minus_plus, cols, LE, w);
  }
  set_add_rowmode(lp.get(), FALSE);
  std::vector<double> objective(n, 1.0);
  std::vector<int> cols(n);
  for (int v = 0; v < n; ++v) {
    cols[v] = v + 1;
    set_upbo(lp.get(), v + 1, h[v]);
    set_lowbo(lp.get(), v + 1, 0.0);
  }
  set_obj_fnex(lp.get(), n, objective.data(), cols.data());
  set_maxim(lp.get());
  set_epsel(lp.get(), 1e-14);
  const int status = solve(lp.get());
  if (status != OPTIMAL && status != PRESOLVED)
    throw Error("lp_solve did not solve the smoothing problem (status " + std::to_string(status) + ")");
  get_variables(lp.get(), h.data());
}

}  // namespace sizemesh
