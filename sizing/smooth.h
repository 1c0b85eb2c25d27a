// Smoothing of the size map to a well-graded one (paper 3.3).
//
// Edge stage (Eq. 12): the sizes closest to h with |h_i - h_j| <= ln(beta) l_ij
// on every background edge and none increased. The feasible set is closed
// under componentwise maximum, so it has a greatest element
//   h*_i = min_j (h_j + d(i, j)),  d = shortest path with edge weights ln(beta_e) l_e,
// which is the exact optimum of Eq. 12; a multi-source Dijkstra gives it in O(E log V).
// Triangle stage (Eq. 11): every triangle with |grad h| > ln(beta) is corrected
// in its own plane (the paper's rule), alternating with the edge stage until
// both hold everywhere.
//
// Inputs:  bg background mesh, m size map (h = initial sizes, ln(beta) bounds)
// Output:  m.h smoothed in place; the returned stats say what changed.
#pragma once

#include <vector>

#include "background/background_mesh.h"
#include "sizing/size_map.h"

namespace sizemesh {

enum class EdgeSolver { Dijkstra, LpSolve };

struct SmoothStats {
  int lowered = 0;              // vertices whose size the smoothing lowered
  double max_reduction = 1;     // largest h_initial / h_smoothed
  int rounds = 0;               // edge/triangle stage alternations
  int triangle_corrections = 0;
  int degenerate_triangles = 0; // zero-area triangles (no gradient to bound)
  int steep_triangles = 0;      // triangles left over their Eq. 11 bound when the rounds ran out
  double t_edge = 0, t_triangle = 0;  // seconds
};

SmoothStats smooth(const BackgroundMesh& bg, SizeMap& m, EdgeSolver solver = EdgeSolver::Dijkstra);

// Edge stage alone (Eq. 12) on h, exact, in place.
void smooth_edges(const BackgroundMesh& bg, const std::vector<double>& edge_log_beta, std::vector<double>& h);

// |grad h| of the linear interpolant on triangle t, in the triangle's plane (Eq. 11);
// negative for a zero-area triangle.
double triangle_gradient(const BackgroundMesh& bg, const std::vector<double>& h, int t);

struct GradationCheck {
  double max_edge_ratio = 0;      // max |h_i - h_j| / (ln(beta) l_ij)
  double max_triangle_ratio = 0;  // max |grad h| / ln(beta)
  std::vector<double> triangle_ratio;  // #T |grad h| / ln(beta) (0 for degenerate)
};
GradationCheck check_gradation(const BackgroundMesh& bg, const SizeMap& m);

}  // namespace sizemesh
