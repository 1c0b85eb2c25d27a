// Edge swap: the diagonal of two triangles sharing an inner edge (a, b) is
// turned into (c, d), their opposite corners, where that raises the worse
// shape in space of the two (local_mesh.h, shape()).
//
// Inputs: fm, fs, the triangles' neighbours nbr (neighbours()) and their
// shapes q; a swap updates all of them.
#pragma once

#include <array>
#include <vector>

#include "mesher/face_mesh.h"

namespace sizemesh::ops {

// May the edge (T1[k], T1[k + 1]) of triangle t1 be swapped: the triangle t2
// across it, where t2 holds the edge (j, as reversed_edge()), and the two
// triangles n1 = (c, a, d), n2 = (d, b, c) that replace t1, t2 with their
// shapes q1, q2. ok when both are valid, on no pole, and the worse of the
// two beats the worse of t1, t2 by more than 1e-6.
struct SwapCheck {
  bool ok = false;
  int t2 = -1, j = -1;
  std::array<int, 3> n1{}, n2{};
  double q1 = 0, q2 = 0;
};
SwapCheck check_swap(const FaceMesh& fm, const FaceSurface& fs, const std::vector<std::array<int, 3>>& nbr,
                     const std::vector<double>& q, int t1, int k);

// The swap check_swap(fm, fs, nbr, q, t1, k) allowed (c.ok): t1, t2 become n1,
// n2, their neighbours and shapes follow.
void apply_swap(FaceMesh& fm, std::vector<std::array<int, 3>>& nbr, std::vector<double>& q, int t1, int k,
                const SwapCheck& c);

// One sweep of diagonal swaps that raise the worse shape of the two
// triangles: each triangle (not on a pole) under shape 0.8, in order, swaps
// its first edge that may be swapped. Returns the swaps made.
int swap_sweep(FaceMesh& fm, const FaceSurface& fs, std::vector<std::array<int, 3>>& nbr);

}  // namespace sizemesh::ops
