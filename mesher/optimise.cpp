#include "mesher/optimise.h"

#include <array>
#include <vector>

#include "mesher/ops/local_mesh.h"
#include "mesher/ops/smooth.h"
#include "mesher/ops/swap.h"

namespace sizemesh {

void optimise(FaceMesh& fm, FaceSurface& fs, int passes, const SplitBounds& bounds) {
  using namespace ops;
  if (passes <= 0 || fm.tris.empty()) return;
  std::vector<std::array<int, 3>> nbr = neighbours(fm);
  // Up to 4 sweeps of swaps, until one makes none.
  auto swaps = [&] {
    for (int k = 0; k < 4 && swap_sweep(fm, fs, nbr) > 0; ++k) {
    }
  };
  // Swaps and smoothing, `passes` times (ops/swap.h, ops/smooth.h).
  for (int p = 0; p < passes; ++p) {
    swaps();
    smooth_sweep(fm, fs);
  }
  swaps();
  // Edges still too long (or too far off the surface) after smoothing are
  // split (ops/split.h, SizeField's length questions).
  for (int round = 0; round < 3 && split_long_edges(fm, fs, bounds, nbr) > 0; ++round) nbr = neighbours(fm);
  // Thin triangles: their inner nodes moved (ops/rescue.h), then those still
  // too close to a neighbour merged into it (ops/collapse.h).
  if (rescue_thin_triangles(fm, fs) > 0) swaps();
  if (collapse_thin_triangles(fm, fs) > 0) {
    nbr = neighbours(fm);
    swaps();
    smooth_sweep(fm, fs);
  }
}

}  // namespace sizemesh
