// A B-rep curve sampled for discretisation: parameters, metric length (paper
// Eq. 1a), arc length and tangent turning from t0, and the size at both ends.
// Shared by the curve discretisation and the sharp-corner rule.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace sizemesh {

struct CurveSamples {
  std::vector<double> t, F;  // F[k] = metric length (integral of ds/h) from t0 to t[k]
  std::vector<double> S, T;  // arc length and tangent turning from t0 to t[k]
  double turning = 0;        // total tangent turning (radians)
  double h0 = 0, h1 = 0;     // size at t0 and t1
  double length() const { return S.empty() ? 0 : S.back(); }
};

// Where a non-decreasing sampled quantity reaches a value: between samples
// k-1 and k, at fraction a.
struct SamplePos {
  size_t k;
  double a;
};

inline SamplePos sample_pos(const std::vector<double>& X, double x) {
  const auto it = std::lower_bound(X.begin(), X.end(), x);
  if (it == X.begin()) return {1, 0.0};
  if (it == X.end()) return {X.size() - 1, 1.0};
  const size_t k = static_cast<size_t>(it - X.begin());
  return {k, X[k] > X[k - 1] ? (x - X[k - 1]) / (X[k] - X[k - 1]) : 0.5};
}

// A sampled quantity linearly interpolated at a position.
inline double sample_at(const std::vector<double>& X, SamplePos p) {
  return X[p.k - 1] + p.a * (X[p.k] - X[p.k - 1]);
}

}  // namespace sizemesh
