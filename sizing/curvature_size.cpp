#include "sizing/curvature_size.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace sizemesh {

double chord_size(double k, double phi_deg) {
  if (!(k > 0) || !std::isfinite(k)) return kNoLimit;
  return 2.0 / k * std::sin(0.5 * phi_deg * kPi / 180.0);  // h_c = 2 r sin(phi_c/2)
}

namespace {
// Under a deviation bound delta, radii r <= delta are below its accuracy: the
// whole arc lies within delta of its chord.
bool below_accuracy(double k, const SizingParams& p) {
  return p.deviation > 0 && std::abs(k) * p.deviation >= 1;
}
// phi_c's size; under a deviation bound delta at least 2 delta: a chord of
// 2 delta lies within delta of any arc of radius delta or more (the smaller
// radii set no size), so a finer angular resolution resolves nothing the bound
// asks for. But never past the chord of a quarter circle: an element spanning
// more of a small radius turns its corners' normals too far apart for a valid
// triangle (on the F-16 at a bound of 1e-3 of the diagonal, elements across
// small radii left an inverted triangle and two crossing pairs).
double angular_size(double k, double phi_deg, const SizingParams& p) {
  return std::max(chord_size(k, phi_deg), std::min(2 * p.deviation, chord_size(k, 90.0)));
}
// Principal curvatures at uv; at a singular point (a pole, an apex) where they
// are undefined, those just beside it, a small step toward the face's uv centre.
bool face_curvatures(const Geometry& g, int face, const Vec2& uv, double& k1, double& k2) {
  if (g.principal_curvatures(face, uv, k1, k2)) return true;
  const UVBox box = g.face_uv_bounds(face);
  const Vec2 centre = 0.5 * (box.lo + box.hi);
  for (double step : {1e-6, 1e-4, 1e-2})
    if (g.principal_curvatures(face, uv + step * (centre - uv), k1, k2)) return true;
  return false;
}

}  // namespace

double triangle_deviation_curvature(double k1, double k2) {
  // An equilateral triangle of side h with its corners on the surface
  // z = (k1 x^2 + k2 y^2) / 2 is off it by k1 h^2 / 8 at the middle of a side
  // across the k1 direction and by (k1 + k2) h^2 / 12 at its centre, whatever
  // its orientation (the mean of the corners' heights): the larger, written as
  // the curvature of an arc whose chord h has that height.
  return std::max(std::abs(k1), std::abs(k1 + k2) * 2.0 / 3.0);
}

double face_curvature_size(const Geometry& g, int face, const Vec2& uv, const SizingParams& p) {
  double k1, k2;
  if (!face_curvatures(g, face, uv, k1, k2) || below_accuracy(k1, p)) return kNoLimit;
  return std::min(angular_size(std::abs(k1), p.face_phi_c(face), p),
                  deviation_size(triangle_deviation_curvature(k1, k2), p.deviation));
}

double curve_curvature_size(const Geometry& g, int curve, double t, const SizingParams& p) {
  double k;
  if (!g.curve_curvature(curve, t, k) || below_accuracy(k, p)) return kNoLimit;
  return std::min(angular_size(k, p.curve_phi_c(curve), p), deviation_size(k, p.deviation));
}

CurvatureMemo::Key CurvatureMemo::key(int face, const Vec2& uv) {
  Key k{face, 0, 0};
  const double u = uv[0], v = uv[1];
  std::memcpy(&k.u, &u, sizeof u);
  std::memcpy(&k.v, &v, sizeof v);
  return k;
}

size_t CurvatureMemo::Hash::operator()(const Key& k) const {
  uint64_t x = k.u * 0x9E3779B97F4A7C15ull ^ (k.v + 0x632BE59BD9B4E019ull + (static_cast<uint64_t>(k.face) << 40));
  x ^= x >> 31;
  return static_cast<size_t>(x * 0xBF58476D1CE4E5B9ull);
}

bool CurvatureMemo::find(int face, const Vec2& uv, double& h) const {
  const auto it = sizes_.find(key(face, uv));
  if (it == sizes_.end()) return false;
  h = it->second;
  return true;
}

void CurvatureMemo::add(int face, const Vec2& uv, double h) { sizes_.emplace(key(face, uv), h); }

double CurvatureMemo::face(const Geometry& g, int face, const Vec2& uv, const SizingParams& p) {
  double h;
  if (find(face, uv, h)) return h;
  h = face_curvature_size(g, face, uv, p);
  add(face, uv, h);
  return h;
}

std::vector<double> curvature_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p,
                                    CurvatureMemo* memo) {
  const int nv = bg.num_vertices();
  std::vector<double> h(nv, kNoLimit);
  // Faces: each vertex at its uv on every face it lies on; the smallest size
  // wins. Each use's size first (looked up in parallel, computed where
  // missing), then the memo gains the new ones.
  const int nu = bg.use_start[nv];
  std::vector<double> at_use(nu);
  std::vector<char> known(nu, 0);
  tbb::parallel_for(0, nv, [&](int v) {
    double best = kNoLimit;
    for (int u = bg.use_start[v]; u < bg.use_start[v + 1]; ++u) {
      const int f = bg.use_face[u];
      const Vec2& uv = bg.patches[f - 1].uv[bg.use_local[u]];
      known[u] = memo && memo->find(f, uv, at_use[u]);
      if (!known[u]) at_use[u] = face_curvature_size(g, f, uv, p);
      best = std::min(best, at_use[u]);
    }
    h[v] = best;
  });
  if (memo)
    for (int v = 0; v < nv; ++v)
      for (int u = bg.use_start[v]; u < bg.use_start[v + 1]; ++u)
        if (!known[u]) memo->add(bg.use_face[u], bg.patches[bg.use_face[u] - 1].uv[bg.use_local[u]], at_use[u]);
  // Curves: the curve's own curvature at its vertices and at its end points.
  auto curve_at = [&](int c, double t, int v) { h[v] = std::min(h[v], curve_curvature_size(g, c, t, p)); };
  for (int v = 0; v < nv; ++v)
    if (bg.dim[v] == 1) curve_at(bg.entity[v], bg.curve_t[v], v);
  for (int c = 1; c <= g.num_curves(); ++c) {
    if (g.curve_degenerated(c)) continue;
    double t0, t1;
    g.curve_range(c, t0, t1);
    if (g.curve_start_point(c) > 0) curve_at(c, t0, g.curve_start_point(c) - 1);
    if (g.curve_end_point(c) > 0) curve_at(c, t1, g.curve_end_point(c) - 1);
  }
  return h;
}

}  // namespace sizemesh
