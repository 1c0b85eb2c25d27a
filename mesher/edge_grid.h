// Spatial search for the advancing front: a uniform grid over a face's uv box
// in which each front edge is listed in every cell its bounding box touches,
// so the edges and nodes near a new triangle are found without a scan.
//
// Inputs:  the uv box, an expected edge count (sets the cell count), edges by id.
// Outputs: query(lo, hi, alive, f) calls f(id) for every edge listed in a
//          cell the box [lo, hi] touches and alive(id) keeps (an edge may come
//          more than once); edges alive(id) refuses are dropped from the cells
//          met, so a front that has long left a crowded part of the face does
//          not pay for its dead edges there. The order of the edges kept is
//          the order they were listed in.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/types.h"

namespace sizemesh {

class EdgeGrid {
 public:
  void init(const Vec2& lo, const Vec2& hi, int n_edges) {
    const Vec2 span = (hi - lo).cwiseMax(Vec2(1e-300, 1e-300));
    lo_ = lo - 1e-6 * span;
    const Vec2 span2 = span * (1 + 2e-6);
    n_ = std::clamp(static_cast<int>(1.5 * std::sqrt(double(n_edges))), 1, 512);
    cell_ = span2 / n_;
    cells_.assign(size_t(n_) * n_, {});
  }
  void insert(int e, const Vec2& a, const Vec2& b) {
    int i0, j0, i1, j1;
    range(a.cwiseMin(b), a.cwiseMax(b), i0, j0, i1, j1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) cells_[size_t(j) * n_ + i].push_back(e);
  }
  template <class Alive, class F>
  void query(const Vec2& lo, const Vec2& hi, Alive&& alive, F&& f) {
    int i0, j0, i1, j1;
    range(lo, hi, i0, j0, i1, j1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        std::vector<int>& cell = cells_[size_t(j) * n_ + i];
        size_t kept = 0;
        for (int e : cell)
          if (alive(e)) cell[kept++] = e, f(e);
        cell.resize(kept);
      }
  }

 private:
  void range(const Vec2& lo, const Vec2& hi, int& i0, int& j0, int& i1, int& j1) const {
    auto ci = [&](double x, int d) {
      const double c = (x - lo_[d]) / cell_[d];
      if (!(c > 0)) return 0;
      return static_cast<int>(std::min<double>(c, n_ - 1));
    };
    i0 = ci(lo.x(), 0);
    j0 = ci(lo.y(), 1);
    i1 = ci(hi.x(), 0);
    j1 = ci(hi.y(), 1);
  }
  Vec2 lo_, cell_;
  int n_ = 1;
  std::vector<std::vector<int>> cells_;
};

}  // namespace sizemesh
