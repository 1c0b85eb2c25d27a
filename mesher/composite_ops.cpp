// The local operations of the composite re-mesh (mesher/composite_mesh.h):
// collapse, split, flip, smoothing and sliding along a curve, each taken only
// when it leaves its star better and on the surface.
#include <algorithm>
#include <array>
#include <cmath>

#include "core/predicates.h"
#include "mesher/composite_mesh.h"

namespace sizemesh::composite_detail {

bool CompositeMesh::collapse(int b, int a, OpCount& count) {
  const bool chain = !free(b);
  if (chain && (corner_[b] || hard_degree_[b] != 2 || !is_hard(a, b))) return false;
  if (corner_[b]) return false;
  const auto across = edge_tris(a, b);
  if (across[0] < 0) return false;
  // Link condition: a and b share no neighbour but the edge's opposite nodes.
  std::vector<int> opposite;
  for (int t : across)
    if (t >= 0)
      for (int m : tris_[t])
        if (m != a && m != b) opposite.push_back(m);
  const auto na = neighbours(a), nb = neighbours(b);
  std::vector<int> common;
  std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common), before_);
  std::sort(opposite.begin(), opposite.end(), before_);
  if (common != opposite) return false;
  int other = -1;  // the chain's next node past b
  if (chain) {
    for (int m : nb)
      if (m != a && is_hard(b, m)) other = m;
    if (other < 0) return false;
    const Vec3 u = (xyz_[a] - xyz_[b]).normalized(), v = (xyz_[other] - xyz_[b]).normalized();
    if (u.dot(v) > -kCos30) return false;  // b is where the chain turns
  }
  for (int m : nb)
    if (m != a && (xyz_[m] - xyz_[a]).norm() > kLongEdge * edge_size(a, m)) return false;
  {
    double old = 0;
    const Vec3 n_b = node_normal(b), n_a = node_normal(a);
    for (int m : nb) old = std::max(old, sag(xyz_[b], n_b, xyz_[m], node_normal(m)));
    for (int m : nb)
      if (m != a && !accurate(xyz_[a], n_a, xyz_[m], node_normal(m), place_[a].face, old)) return false;
  }

  const std::vector<int> old = node_tris_[b];
  const double before = star_min_angle(old);
  double after = 180;
  std::vector<std::array<int, 3>> made;
  for (int t : old) {
    if (t == across[0] || t == across[1]) continue;
    std::array<int, 3> nt = tris_[t];
    for (int& m : nt)
      if (m == b) m = a;
    const Vec3 n0 = normal(tris_[t]), n1 = normal(nt);
    if (n1.norm() <= 1e-12 * n0.norm() || n0.dot(n1) < kCos45 * n0.norm() * n1.norm()) return false;
    after = std::min(after, min_angle_deg(xyz_[nt[0]], xyz_[nt[1]], xyz_[nt[2]]));
    made.push_back(nt);
  }
  if (after < std::min(before, kFairDeg)) return false;
  std::vector<std::array<Vec3, 3>> corners;
  for (const auto& nt : made) corners.push_back({xyz_[nt[0]], xyz_[nt[1]], xyz_[nt[2]]});
  if (free(a) && !facing(corners, place_[a])) return false;  // a kept node's faces turn apart

  std::vector<int> faces;
  for (int t : old)
    if (t != across[0] && t != across[1]) faces.push_back(tri_face_[t]);
  for (int t : old) kill(t);
  for (size_t i = 0; i < made.size(); ++i) add_tri(made[i], faces[i]);
  if (chain) {
    hard_.erase(edge_key(a, b));
    hard_.erase(edge_key(b, other));
    hard_.insert(edge_key(a, other));
    hard_degree_[b] = 0;
  }
  ++count.collapsed;
  return true;
}

bool CompositeMesh::split(int a, int b, OpCount& count) {
  if (is_hard(a, b)) return false;
  const auto across = edge_tris(a, b);
  if (across[0] < 0 || across[1] < 0) return false;
  const double len = (xyz_[a] - xyz_[b]).norm();
  Vec3 x;
  Place at;
  if (!project(0.5 * (xyz_[a] + xyz_[b]), 0.25 * len, x, at)) return false;
  std::vector<std::pair<std::array<int, 3>, int>> made;
  double before = 180, after = 180;
  for (int t : across) {
    const auto& tr = tris_[t];
    const int k = static_cast<int>(std::find(tr.begin(), tr.end(), a) - tr.begin());
    const bool ab = tr[(k + 1) % 3] == b;  // a -> b in t
    const int c = tr[(k + (ab ? 2 : 1)) % 3];
    before = std::min(before, min_angle_deg(xyz_[tr[0]], xyz_[tr[1]], xyz_[tr[2]]));
    const std::array<int, 3> t1 = ab ? std::array<int, 3>{a, -1, c} : std::array<int, 3>{-1, a, c};
    const std::array<int, 3> t2 = ab ? std::array<int, 3>{-1, b, c} : std::array<int, 3>{b, -1, c};
    for (const auto& nt : {t1, t2}) {
      std::array<Vec3, 3> p;
      for (int i = 0; i < 3; ++i) p[i] = nt[i] < 0 ? x : xyz_[nt[i]];
      const Vec3 n0 = normal(tr), n1 = (p[1] - p[0]).cross(p[2] - p[0]);
      if (n0.dot(n1) < kCos30 * n0.norm() * n1.norm()) return false;
      after = std::min(after, min_angle_deg(p[0], p[1], p[2]));
      made.push_back({nt, tri_face_[t]});
    }
  }
  if (after < std::min(before, kFairDeg)) return false;
  std::vector<std::array<Vec3, 3>> corners;
  for (const auto& [nt, f] : made) {
    std::array<Vec3, 3> p;
    for (int i = 0; i < 3; ++i) p[i] = nt[i] < 0 ? x : xyz_[nt[i]];
    corners.push_back(p);
  }
  if (!facing(corners, at)) return false;
  const int n = add_node(x, at);
  for (int t : across) kill(t);
  for (auto& [nt, f] : made) {
    for (int& m : nt)
      if (m < 0) m = n;
    add_tri(nt, f);
  }
  ++count.split;
  return true;
}

bool CompositeMesh::flip(int a, int b, OpCount& count) {
  if (is_hard(a, b)) return false;
  auto across = edge_tris(a, b);
  if (across[0] < 0 || across[1] < 0) return false;
  const auto& t0 = tris_[across[0]];
  const int k = static_cast<int>(std::find(t0.begin(), t0.end(), a) - t0.begin());
  if (t0[(k + 1) % 3] != b) std::swap(across[0], across[1]);  // across[0] runs a -> b
  const auto& t1 = tris_[across[0]];
  const auto& t2 = tris_[across[1]];
  int c = -1, d = -1;
  for (int m : t1)
    if (m != a && m != b) c = m;
  for (int m : t2)
    if (m != a && m != b) d = m;
  if (c < 0 || d < 0 || c == d) return false;
  const double before = star_min_angle({across[0], across[1]});
  if (before >= kSmoothBelow) return false;  // good already
  const double after = std::min(min_angle_deg(xyz_[c], xyz_[a], xyz_[d]), min_angle_deg(xyz_[d], xyz_[b], xyz_[c]));
  if (after < before + 0.5) return false;
  for (int t : node_tris_[c])  // c and d joined already
    if (std::find(tris_[t].begin(), tris_[t].end(), d) != tris_[t].end()) return false;
  const std::array<int, 3> n1{c, a, d}, n2{d, b, c};
  const Vec3 o = normal(t1).normalized() + normal(t2).normalized();
  const Vec3 m1 = normal(n1), m2 = normal(n2);
  if (m1.dot(m2) < kCos30 * m1.norm() * m2.norm()) return false;
  if (o.dot(m1) < kCos30 * o.norm() * m1.norm() || o.dot(m2) < kCos30 * o.norm() * m2.norm()) return false;
  if (!accurate(xyz_[c], node_normal(c), xyz_[d], node_normal(d), place_[c].face,
                sag(xyz_[a], node_normal(a), xyz_[b], node_normal(b))))
    return false;
  const int f1 = tri_face_[across[0]], f2 = tri_face_[across[1]];
  kill(across[0]);
  kill(across[1]);
  add_tri(n1, f1);
  add_tri(n2, f2);
  ++count.flipped;
  return true;
}

bool CompositeMesh::smooth(int n, OpCount& count) {
  if (!free(n) || node_tris_[n].empty()) return false;
  // Only stars with a triangle under kSmoothBelow: the rest are good already.
  const double before = star_min_angle(node_tris_[n]);
  if (before >= kSmoothBelow) return false;
  const auto nb = neighbours(n);
  Vec3 centroid = Vec3::Zero(), nsum = Vec3::Zero();
  for (int m : nb) centroid += xyz_[m];
  centroid /= static_cast<double>(nb.size());
  for (int t : node_tris_[n]) nsum += normal(tris_[t]);
  if (nsum.norm() <= 0) return false;
  const Vec3 nn = nsum.normalized();
  Vec3 step = centroid - xyz_[n];
  step -= nn * nn.dot(step);
  if (step.norm() < 1e-3 * size(n)) return false;
  Vec3 x;
  Place at;
  if (!project(xyz_[n] + step, 0.5 * size(n), x, at)) return false;
  const Vec3 n_old = node_normal(n), n_new = surface_normal(at);
  for (int m : nb) {
    const Vec3 nm = node_normal(m);
    if (!accurate(x, n_new, xyz_[m], nm, at.face, sag(xyz_[n], n_old, xyz_[m], nm))) return false;
  }
  const Vec3 keep = xyz_[n];
  std::vector<Vec3> old_normals;
  for (int t : node_tris_[n]) old_normals.push_back(normal(tris_[t]));
  xyz_[n] = x;
  bool ok = true;
  // Each triangle turns by at most 30 degrees, or turns towards the surface
  // (a triangle the union left standing across it is laid down).
  for (size_t i = 0; i < node_tris_[n].size() && ok; ++i) {
    const Vec3 m = normal(tris_[node_tris_[n][i]]);
    const Vec3& o = old_normals[i];
    ok = m.dot(o) >= kCos30 * m.norm() * o.norm() ||
         (!n_new.isZero() && m.norm() > 0 && o.norm() > 0 && m.dot(n_new) / m.norm() > o.dot(n_new) / o.norm());
  }
  if (ok) {
    std::vector<std::array<Vec3, 3>> corners;
    for (int t : node_tris_[n]) corners.push_back({xyz_[tris_[t][0]], xyz_[tris_[t][1]], xyz_[tris_[t][2]]});
    ok = facing(corners, at);
  }
  const double after = ok ? star_min_angle(node_tris_[n]) : 0;
  if (!ok || after < std::min(before, kFairDeg + 5)) {
    xyz_[n] = keep;
    return false;
  }
  place_[n] = at;
  normal_[n] = n_new;
  has_normal_[n] = 1;
  int hint = -1;
  size_[n] = h_.at(at.face, at.uv, hint);
  for (int t : node_tris_[n]) changed_[t] = 1;
  ++count.smoothed;
  return true;
}

double CompositeMesh::curve_parameter(int c, const Vec3& x) const {
  double t0, t1;
  g_.curve_range(c, t0, t1);
  if (!(t1 > t0)) return NAN;
  constexpr int kSamples = 32;
  double t = t0, best = HUGE_VAL;
  for (int i = 0; i <= kSamples; ++i) {
    const double ti = t0 + (t1 - t0) * i / kSamples;
    const double d = (g_.eval_curve(c, ti) - x).squaredNorm();
    if (d < best) best = d, t = ti;
  }
  for (int it = 0; it < 20; ++it) {  // Gauss-Newton on |C(t) - x|^2
    const Vec3 d = g_.curve_tangent(c, t);
    const double dd = d.squaredNorm();
    if (!(dd > 0)) break;
    const double step = (x - g_.eval_curve(c, t)).dot(d) / dd;
    t = std::clamp(t + step, t0, t1);
    if (std::abs(step) <= 1e-14 * (t1 - t0)) break;
  }
  return t;
}

bool CompositeMesh::slide(int n, OpCount& count) {
  const int c = curve_[n];
  if (!c || corner_[n] || hard_degree_[n] != 2 || node_tris_[n].empty()) return false;
  const double before = star_min_angle(node_tris_[n]);
  if (before >= kSmoothBelow) return false;
  std::vector<int> chain;
  for (int m : neighbours(n))
    if (is_hard(n, m)) chain.push_back(m);
  if (chain.size() != 2) return false;
  const double tn = curve_parameter(c, xyz_[n]);
  if (!std::isfinite(tn) || (g_.eval_curve(c, tn) - xyz_[n]).norm() > 1e-6 * (xyz_[chain[0]] - xyz_[n]).norm())
    return false;  // not where the curve is (a node the union moved)
  const Vec3 keep = xyz_[n];
  std::vector<Vec3> old_normals;
  for (int t : node_tris_[n]) old_normals.push_back(normal(tris_[t]));
  // The chords to the chain neighbours stay as accurate along the curve as
  // before (their height from the curve's tangents, as sag() from normals).
  auto unit_tangent = [&](double t) { return Vec3(g_.curve_tangent(c, t).normalized()); };
  std::array<Vec3, 2> end_tangent;
  double old_sag = 0;
  for (int i = 0; i < 2; ++i) {
    const double tm = curve_parameter(c, xyz_[chain[i]]);
    end_tangent[i] = std::isfinite(tm) ? unit_tangent(tm) : Vec3::Zero();
    old_sag = std::max(old_sag, sag(keep, unit_tangent(tn), xyz_[chain[i]], end_tangent[i]));
  }
  Vec3 best_x = keep;
  double best = before + 1.0;  // a degree better at least
  for (int m : chain)
    for (int k = 1; k <= 4; ++k) {
      const double t = curve_parameter(c, keep + (xyz_[m] - keep) * (k / 8.0));
      if (!std::isfinite(t)) continue;
      xyz_[n] = g_.eval_curve(c, t);
      bool ok = true;
      for (int i = 0; i < 2 && ok; ++i)
        ok = accurate(xyz_[n], unit_tangent(t), xyz_[chain[i]], end_tangent[i], place_[n].face, old_sag);
      for (size_t i = 0; i < node_tris_[n].size() && ok; ++i) {
        const Vec3 nn = normal(tris_[node_tris_[n][i]]);
        ok = nn.dot(old_normals[i]) >= kCos30 * nn.norm() * old_normals[i].norm();
      }
      const double angle = ok ? star_min_angle(node_tris_[n]) : 0;
      if (angle > best) best = angle, best_x = xyz_[n];
    }
  xyz_[n] = keep;
  if (best_x == keep) return false;
  xyz_[n] = best_x;
  slid_[n] = 1;
  for (int t : node_tris_[n]) changed_[t] = 1;
  ++count.slid;
  return true;
}

}  // namespace sizemesh::composite_detail
