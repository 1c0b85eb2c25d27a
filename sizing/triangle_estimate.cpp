#include "sizing/triangle_estimate.h"

#include <algorithm>
#include <cmath>

namespace sizemesh {
namespace {

// First divided difference of g(x) = -ln x.
double dd1(double a, double b) {
  const double x = (b - a) / a;
  if (std::abs(x) < 1e-8) return -(1.0 - 0.5 * x) / a;
  return -std::log1p(x) / (b - a);
}

}  // namespace

// Exact integral of 1/h^2 over a triangle of area A where h is linear with
// corner values h1..h3 > 0: by the Hermite-Genocchi formula it is 2A times
// the second divided difference of -ln at (h1, h2, h3); A / h^2 when equal.
// (A midpoint rule overestimates badly on long triangles whose size grows
// away from a small feature.)
double inverse_square_integral(double area, double h1, double h2, double h3) {
  double h[3] = {h1, h2, h3};
  std::sort(h, h + 3);
  if (!(h[0] > 0)) return 0;
  const double spread = (h[2] - h[0]) / h[0];
  if (spread < 1e-4) {
    const double m = (h[0] + h[1] + h[2]) / 3.0;
    return area / (m * m);
  }
  return 2.0 * area * (dd1(h[1], h[2]) - dd1(h[0], h[1])) / (h[2] - h[0]);
}

Limit TriangleEstimate::dominant() const {
  return static_cast<Limit>(std::max_element(by_limit.begin(), by_limit.end()) - by_limit.begin());
}

TriangleEstimate estimate_triangles(const BackgroundMesh& bg, const std::vector<double>& h,
                                    const std::vector<Limit>& limit, int num_faces) {
  const double per_area = 4.0 / std::sqrt(3.0);  // triangles per h^2 of area
  TriangleEstimate e;
  e.per_face.assign(static_cast<size_t>(std::max(num_faces, 0)) + 1, 0.0);
  for (int t = 0; t < bg.num_triangles(); ++t) {
    const auto& v = bg.tris[t];
    const Vec3& a = bg.xyz[v[0]];
    const double area = 0.5 * (bg.xyz[v[1]] - a).cross(bg.xyz[v[2]] - a).norm();
    const double n = per_area * inverse_square_integral(area, h[v[0]], h[v[1]], h[v[2]]);
    if (!std::isfinite(n)) continue;
    const int f = bg.tri_face[t];
    if (f > 0 && f <= num_faces) e.per_face[f] += n;
    e.total += n;
    if (!limit.empty()) {
      int smallest = v[0];
      for (int k = 1; k < 3; ++k)
        if (h[v[k]] < h[smallest]) smallest = v[k];
      e.by_limit[static_cast<int>(limit[smallest])] += n;
    }
  }
  return e;
}

}  // namespace sizemesh
