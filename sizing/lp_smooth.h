// Reference solver for the edge stage (paper Eq. 12) with lp_solve, as the
// paper did: maximise sum(h') subject to |h'_i - h'_j| <= ln(beta_e) l_ij on
// every background edge and 0 <= h'_i <= h_i. Its optimum is the same greatest
// element smooth_edges() computes exactly; kept to check that, and selectable
// from the command line.
//
// Inputs:  bg background mesh, edge_log_beta #E, h #V initial sizes
// Output:  h replaced by the LP solution. Throws Error when lp_solve fails.
#pragma once

#include <vector>

#include "background/background_mesh.h"

namespace sizemesh {

void smooth_edges_lp(const BackgroundMesh& bg, const std::vector<double>& edge_log_beta, std::vector<double>& h);

}  // namespace sizemesh
