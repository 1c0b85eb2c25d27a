#include "mesher/snap.h"

#include <Eigen/Dense>
#include <cmath>

namespace sizemesh {

bool snap(const Geometry& g, const std::vector<int>& faces, std::vector<Vec2>& uv, Vec3& x, double reach,
          double tol) {
  const Vec3 start = x;
  const size_t k = faces.size();
  for (int it = 0; it < 12; ++it) {
    Eigen::MatrixXd n(k, 3);
    Eigen::VectorXd d(k);
    for (size_t i = 0; i < k; ++i) {
      if (!g.project_to_face(faces[i], x, uv[i])) return false;
      const SurfaceD1 s = g.eval_face(faces[i], uv[i]);
      Vec3 normal = s.du.cross(s.dv);
      if (!(normal.norm() > 0)) return false;
      normal.normalize();
      n.row(i) = normal.transpose();
      d(i) = normal.dot(s.p);
    }
    // y = x - N^+ (N x - d): on every tangent plane, nearest to x.
    const Eigen::VectorXd r = n * x - d;
    const Vec3 step = n.completeOrthogonalDecomposition().solve(r);
    x -= step;
    if ((x - start).norm() > reach || !std::isfinite(x.x())) return false;
    if (step.norm() <= tol) {
      for (size_t i = 0; i < k; ++i)
        if (!g.project_to_face(faces[i], x, uv[i])) return false;
      return true;
    }
  }
  return false;
}

}  // namespace sizemesh
