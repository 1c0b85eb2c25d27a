#include "mesher/ops/local_mesh.h"

#include <algorithm>
#include <cstdint>

#include "core/predicates.h"
#include "core/mesh_topology.h"

namespace sizemesh::ops {
namespace {

constexpr double kCosMin = 0.5;    // triangle normal against the surface normal
constexpr double kCosAgree = 0.90630778703665;  // cos 25 deg: corner normals that agree

// Triangle tr's corners in uv and their samples, with node i moved to (uv, s).
void moved_corners(const FaceMesh& fm, const std::array<int, 3>& tr, int i, const Vec2& uv, const SurfaceSample& s,
                   Vec2 (&u)[3], const SurfaceSample* (&p)[3]) {
  for (int k = 0; k < 3; ++k) {
    u[k] = tr[k] == i ? uv : fm.uv[tr[k]];
    p[k] = tr[k] == i ? &s : &fm.s[tr[k]];
  }
}

}  // namespace

double shape(const Vec2& ua, const Vec2& ub, const Vec2& uc, const SurfaceSample& sa, const SurfaceSample& sb,
             const SurfaceSample& sc, const FaceSurface& fs) {
  const double o = orient(ua, ub, uc);
  const double scale = (ub - ua).norm() * ((uc - ua).norm() + (uc - ub).norm());
  if (!(o > 1e-10 * scale)) return -1;
  const Vec3 nt = (sb.p - sa.p).cross(sc.p - sa.p);
  const double lt = nt.norm();
  if (!(lt > 0)) return -1;
  const SurfaceSample* corners[3] = {&sa, &sb, &sc};
  bool agree = true;
  for (int k = 0; k < 3; ++k) {
    const Vec3& n = corners[k]->n;  // zero on poles
    if (n.squaredNorm() > 0 && nt.dot(n) < kCosMin * lt) return -1;
    agree = agree && n.squaredNorm() > 0 && n.dot(corners[(k + 1) % 3]->n) > kCosAgree;
  }
  // Where the corners' normals agree within 25 degrees, the surface's at the
  // centroid lies among them (the elements are small against the curvature):
  // within 85 degrees of the triangle's, not turned. Else it is evaluated.
  if (!agree && fs.turned_at_centroid(ua, ub, uc, nt)) return -1;
  return triangle_quality(sa.p, sb.p, sc.p);
}

double shape(const FaceMesh& fm, const FaceSurface& fs, const std::array<int, 3>& t) {
  return shape(fm.uv[t[0]], fm.uv[t[1]], fm.uv[t[2]], fm.s[t[0]], fm.s[t[1]], fm.s[t[2]], fs);
}

double final_min_angle(const FaceMesh& fm, const std::array<int, 3>& t) {
  return min_angle_deg(fm.position(t[0]), fm.position(t[1]), fm.position(t[2]));
}

std::vector<std::array<int, 3>> neighbours(const FaceMesh& fm) { return triangle_neighbours(fm.tris); }

void repoint(std::vector<std::array<int, 3>>& nbr, int t, int from, int to) {
  if (t < 0) return;
  for (int k = 0; k < 3; ++k)
    if (nbr[t][k] == from) nbr[t][k] = to;
}

int reversed_edge(const std::array<int, 3>& T2, int a, int b) {
  for (int j = 0; j < 3; ++j)
    if (T2[j] == b && T2[(j + 1) % 3] == a) return j;
  return -1;
}

Balls::Balls(const FaceMesh& fm) { vertex_triangles(fm.num_nodes(), fm.tris, start, tri_of); }

BallMeasure measure_ball(const FaceMesh& fm, const FaceSurface& fs, const Balls& b, int i, const Vec2& uv,
                         const SurfaceSample& s, const std::vector<char>* lenient) {
  BallMeasure m;
  for (int e = b.start[i]; e < b.start[i + 1] && m.valid; ++e) {
    const auto& tr = fm.tris[b.tri_of[e]];
    Vec2 u[3];
    const SurfaceSample* p[3];
    moved_corners(fm, tr, i, uv, s, u, p);
    if (fm.pole_triangle(tr)) {
      m.valid = orient(u[0], u[1], u[2]) > 0;
      continue;
    }
    if (lenient && (*lenient)[e - b.start[i]]) {
      const Vec3 nt = (p[1]->p - p[0]->p).cross(p[2]->p - p[0]->p);
      m.valid = orient(u[0], u[1], u[2]) > 0 && !fs.turned_at_centroid(u[0], u[1], u[2], nt);
    } else {
      const double q = shape(u[0], u[1], u[2], *p[0], *p[1], *p[2], fs);
      m.valid = q >= 0;
      m.shape = std::min(m.shape, q);
    }
    const double angle = min_angle_deg(p[0]->p, p[1]->p, p[2]->p);
    m.angle = std::min(m.angle, angle);
    m.thin += angle < kSliverDeg;
  }
  return m;
}

bool ball_keeps_shape(const FaceMesh& fm, const FaceSurface& fs, const Balls& b, int i, const Vec2& uv,
                      const SurfaceSample& s, double worst) {
  for (int e = b.start[i]; e < b.start[i + 1]; ++e) {
    const auto& tr = fm.tris[b.tri_of[e]];
    Vec2 u[3];
    const SurfaceSample* p[3];
    moved_corners(fm, tr, i, uv, s, u, p);
    if (fm.pole_triangle(tr)) {
      if (!(orient(u[0], u[1], u[2]) > 0)) return false;
      continue;
    }
    const double q = shape(u[0], u[1], u[2], *p[0], *p[1], *p[2], fs);
    if (!(q >= 0) || q < worst) return false;
  }
  return true;
}

void apply_move(FaceMesh& fm, int i, const NodeMove& m) {
  fm.uv[i] = m.uv;
  fm.s[i] = m.s;
}

}  // namespace sizemesh::ops
