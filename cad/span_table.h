// Every span of a B-spline surface as a polynomial, built on first use and
// kept (OCCT's BSplSLib_Cache, one per span), shared by all threads.
//
// OCCT's adaptor caches the one span it evaluated last: the mesher's
// evaluations hop between spans (a front's candidates, its checks, the
// optimiser's stars), and each hop rebuilt the span's polynomial, which
// costs as much as a de Boor evaluation (a tenth of the M6's run). Here a
// span's polynomial is built once and an evaluation is a span lookup (a
// binary search in the knots) and a polynomial evaluation. The span an
// evaluation uses depends on its parameters only, never on the previous
// call, so the result does not depend on the order of evaluations.
// OpenCASCADE side: cad/ only.
#pragma once

#include <BSplCLib_CacheParams.hxx>
#include <BSplSLib_Cache.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Surface.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <atomic>
#include <cstddef>
#include <memory>
#include <vector>

namespace sizemesh {

class SpanTable {
 public:
  // Null when s is not a B-spline surface (possibly trimmed) or its table
  // would take more than max_bytes.
  static std::unique_ptr<SpanTable> make(const Handle(Geom_Surface)& s, size_t max_bytes);
  ~SpanTable();
  SpanTable(const SpanTable&) = delete;
  SpanTable& operator=(const SpanTable&) = delete;

  // The bytes the table takes once every span is built.
  size_t bytes() const { return bytes_; }
  // Point and first derivatives; false on a span of zero length (the caller
  // evaluates another way).
  bool d1(double u, double v, gp_Pnt& p, gp_Vec& du, gp_Vec& dv) const;

 private:
  explicit SpanTable(const Handle(Geom_BSplineSurface)& s);
  const BSplSLib_Cache* span(double u, double v) const;
  static int locate(const BSplCLib_CacheParams& p, const std::vector<double>& knots, int lower, double t);

  Handle(Geom_BSplineSurface) s_;
  BSplCLib_CacheParams pu_, pv_;
  std::vector<double> ku_, kv_;  // flat knots, 0-based (OCCT index - lower)
  int lower_u_, lower_v_, nu_, nv_;
  size_t bytes_ = 0;
  mutable std::unique_ptr<std::atomic<BSplSLib_Cache*>[]> spans_;  // [iu * nv_ + iv]
};

}  // namespace sizemesh
