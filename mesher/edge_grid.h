// Spatial search for the advancing front: a uniform grid over a face's uv box
// in which each front edge is listed in every cell its bounding box touches,
// so the edges and nodes near a new triangle are found without a scan.
//
// Inputs:  the uv box, an expected edge count (sets the cell count), the
//          ratio of the box's length in space along u to that along v (the
//          cells are about square in space, so a face far longer one way
//          than the other, as a leading-edge strip in a unit parameter
//          square, does not list each edge in hundreds of cells), edges by id.
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
  void init(const Vec2& lo, const Vec2& hi, int n_edges, double aspect = 1.0) {
    const Vec2 span = (hi - lo).cwiseMax(Vec2(1e-300, 1e-300));
    lo_ = lo - 1e-6 * span;
    const Vec2 span2 = span * (1 + 2e-6);
    // Within a factor 4 of square the square grid does as well.
    if (!(aspect > 0) || !std::isfinite(aspect) || (aspect > 0.25 && aspect < 4)) aspect = 1.0;
    aspect = std::clamp(aspect, 1e-4, 1e4);
    // 1.5 sqrt(n) cells a side on a square, at most 512 x 512 cells in all.
    const double n = double(n_edges), scale = std::min(1.0, 512.0 / (1.5 * std::sqrt(n)));
    nu_ = std::clamp(static_cast<int>(scale * 1.5 * std::sqrt(n * aspect)), 1, 512 * 512);
    nv_ = std::clamp(static_cast<int>(scale * 1.5 * std::sqrt(n / aspect)), 1, 512 * 512);
    if (aspect == 1.0) nu_ = nv_ = std::clamp(static_cast<int>(1.5 * std::sqrt(n)), 1, 512);
    cell_ = Vec2(span2.x() / nu_, span2.y() / nv_);
    cells_.assign(size_t(nu_) * nv_, {});
  }
  void insert(int e, const Vec2& a, const Vec2& b) {
    int i0, j0, i1, j1;
    range(a.cwiseMin(b), a.cwiseMax(b), i0, j0, i1, j1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) cells_[size_t(j) * nu_ + i].push_back(e);
  }
  template <class Alive, class F>
  void query(const Vec2& lo, const Vec2& hi, Alive&& alive, F&& f) {
    int i0, j0, i1, j1;
    range(lo, hi, i0, j0, i1, j1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        std::vector<int>& cell = cells_[size_t(j) * nu_ + i];
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
      return static_cast<int>(std::min<double>(c, (d == 0 ? nu_ : nv_) - 1));
    };
    i0 = ci(lo.x(), 0);
    j0 = ci(lo.y(), 1);
    i1 = ci(hi.x(), 0);
    j1 = ci(hi.y(), 1);
  }
  Vec2 lo_, cell_;
  int nu_ = 1, nv_ = 1;
  std::vector<std::vector<int>> cells_;
};

}  // namespace sizemesh
