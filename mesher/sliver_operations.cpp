// Cleaner's local operations on a thin junction triangle (collapse, flip, pinch) and the tests they share.
#include "mesher/sliver_cleaner.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace sizemesh::junction_slivers_detail {
namespace {

constexpr double kLeanCos = 0.70710678118654752;  // cos 45 deg: a triangle's largest lean off its surface

}  // namespace

std::vector<int> Cleaner::faces(int n) const {
  std::vector<int> f;
  for (int t : node_tris_[n])
    if (!dead_[t]) f.push_back(s_.tri_face[t]);
  std::sort(f.begin(), f.end());
  f.erase(std::unique(f.begin(), f.end()), f.end());
  return f;
}

std::vector<int> Cleaner::neighbours(int n) const {
  std::vector<int> out;
  for (int t : node_tris_[n])
    if (!dead_[t])
      for (int m : s_.tris[t])
        if (m != n) out.push_back(m);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

double Cleaner::lean(int f, const std::array<Vec3, 3>& x, const std::array<Vec2, 3>& uv) const {
  const Vec3 n = (x[1] - x[0]).cross(x[2] - x[0]);
  const double ln = n.norm();
  if (!(ln > 0)) return -1;
  SurfaceD1 d;
  try {
    d = g_.eval_face(f, (uv[0] + uv[1] + uv[2]) / 3.0);
  } catch (const EvaluationError&) {
    return -1;
  }
  Vec3 ns = d.du.cross(d.dv);
  if (g_.face_reversed(f)) ns = -ns;
  const double ls = ns.norm();
  if (!(ls > 0) || !std::isfinite(ls)) return 1;
  return n.dot(ns) / (ln * ls);
}

double Cleaner::lean(int t) const {
  const auto& tr = s_.tris[t];
  return lean(s_.tri_face[t], {s_.xyz[tr[0]], s_.xyz[tr[1]], s_.xyz[tr[2]]}, s_.tri_uv[t]);
}

bool Cleaner::uv_in(int n, int f, const Vec2& near, Vec2& out) const {
  for (int t : node_tris_[n])
    if (!dead_[t] && s_.tri_face[t] == f) {
      out = unwrap_uv(g_, f, s_.tri_uv[t][corner(t, n)], near);
      return true;
    }
  out = near;
  if (!g_.project_to_face(f, s_.xyz[n], out)) return false;
  out = unwrap_uv(g_, f, out, near);
  return true;
}

bool Cleaner::thin_ear(int f, const std::array<int, 3>& n, const std::function<int(int, int)>& face_across) const {
  const auto ang = corner_angles_deg(s_.xyz[n[0]], s_.xyz[n[1]], s_.xyz[n[2]]);
  const double least = std::min({ang[0], ang[1], ang[2]});
  if (!(least < kSliverDeg)) return false;
  for (int k = 0; k < 3; ++k)
    if (ang[k] > least && face_across(n[k], n[(k + 1) % 3]) != f && face_across(n[(k + 2) % 3], n[k]) != f)
      return true;
  return false;
}

double Cleaner::size_at(int n) const {
  double best = HUGE_VAL;
  for (int t : node_tris_[n]) {
    if (dead_[t]) continue;
    int hint = -1;
    best = std::min(best, h_.at(s_.tri_face[t], s_.tri_uv[t][corner(t, n)], hint));
  }
  return best;
}

bool Cleaner::collapse(int b, int a, double reach, bool apply, Shape& before, Shape& after) {
  if (s_.node_dim[b] == 0) return false;
  const std::vector<int> fb = faces(b), fa = faces(a);
  bool within = std::includes(fa.begin(), fa.end(), fb.begin(), fb.end());
  if (s_.node_dim[b] == 1 && s_.node_dim[a] == 1 && s_.node_entity[a] != s_.node_entity[b]) within = false;
  if (!within && !((s_.xyz[a] - s_.xyz[b]).norm() < std::max(reach, kSliverTan * size_at(b)))) return false;
  const std::vector<int> tb = alive(b);
  std::vector<int> shared, opposite;
  for (int t : tb)
    if (corner(t, a) < 3) {
      shared.push_back(t);
      for (int n : s_.tris[t])
        if (n != a && n != b) opposite.push_back(n);
    }
  if (shared.size() != 2) return false;
  std::sort(opposite.begin(), opposite.end());
  const std::vector<int> na = neighbours(a), nb = neighbours(b);
  std::vector<int> common;
  std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
  if (common != opposite) return false;
  double limit = kLeanCos;
  for (int t : tb) {
    const auto& tr = s_.tris[t];
    before.add(s_.xyz[tr[0]], s_.xyz[tr[1]], s_.xyz[tr[2]]);
    limit = std::min(limit, lean(t));
  }
  limit = std::max(limit, 0.0);
  std::vector<std::pair<int, Vec2>> moved;  // triangle, a's uv in it
  for (int t : tb) {
    if (corner(t, a) < 3) continue;
    const int k = corner(t, b), f = s_.tri_face[t];
    Vec2 uv;
    if (!uv_in(a, f, s_.tri_uv[t][k], uv)) return false;
    std::array<Vec3, 3> x{s_.xyz[s_.tris[t][0]], s_.xyz[s_.tris[t][1]], s_.xyz[s_.tris[t][2]]};
    std::array<Vec2, 3> w = s_.tri_uv[t];
    x[k] = s_.xyz[a];
    w[k] = uv;
    if (!(lean(f, x, w) > limit)) return false;
    after.add(x[0], x[1], x[2]);
    moved.emplace_back(t, uv);
  }
  // The face across edge (u, v) once b is merged into a.
  auto face_across = [&](int self, int u, int v) {
    std::vector<int> around = alive(u);
    if (u == a) around.insert(around.end(), tb.begin(), tb.end());
    for (int t : around) {
      if (t == self || std::find(shared.begin(), shared.end(), t) != shared.end()) continue;
      auto c = s_.tris[t];
      for (int& n : c) n = n == b ? a : n;
      if (std::find(c.begin(), c.end(), v) != c.end()) return s_.tri_face[t];
    }
    return -1;
  };
  for (const auto& [t, uv] : moved) {
    auto c = s_.tris[t];
    for (int& n : c) n = n == b ? a : n;
    if (thin_ear(s_.tri_face[t], c, [&](int u, int v) { return face_across(t, u, v); })) return false;
  }
  if (!apply) return true;
  for (int t : shared) dead_[t] = 1;
  for (const auto& [t, uv] : moved) {
    const int k = corner(t, b);
    s_.tris[t][k] = a;
    s_.tri_uv[t][k] = uv;
    node_tris_[a].push_back(t);
  }
  node_tris_[b].clear();
  merged_into_[b] = a;
  return true;
}

bool Cleaner::across_largest(int t, Across& x) const {
  const auto tr = s_.tris[t];
  const auto ang = corner_angles_deg(s_.xyz[tr[0]], s_.xyz[tr[1]], s_.xyz[tr[2]]);
  x.kr = static_cast<int>(std::max_element(ang.begin(), ang.end()) - ang.begin());
  x.angle = ang[x.kr];
  x.r = tr[x.kr], x.p = tr[(x.kr + 1) % 3], x.q = tr[(x.kr + 2) % 3];
  int across = 0;
  x.t2 = -1;
  for (int u : node_tris_[x.p])
    if (u != t && !dead_[u] && corner(u, x.q) < 3) x.t2 = u, ++across;
  if (across != 1) return false;
  x.o = -1;
  for (int n : s_.tris[x.t2])
    if (n != x.p && n != x.q) x.o = n;
  const std::vector<int> nr = neighbours(x.r);
  return x.o >= 0 && x.o != x.r && !std::binary_search(nr.begin(), nr.end(), x.o);
}

bool Cleaner::flip(int t, bool apply, Shape& before, Shape& after) {
  Across x;
  if (!across_largest(t, x) || s_.tri_face[x.t2] != s_.tri_face[t]) return false;
  const int r = x.r, p = x.p, q = x.q, kr = x.kr, t2 = x.t2, o = x.o, f = s_.tri_face[t];
  const Vec2 ur = s_.tri_uv[t][kr], up = s_.tri_uv[t][(kr + 1) % 3], uq = s_.tri_uv[t][(kr + 2) % 3];
  const Vec2 uo = s_.tri_uv[t2][corner(t2, o)] + (up - s_.tri_uv[t2][corner(t2, p)]);
  before.add(s_.xyz[r], s_.xyz[p], s_.xyz[q]);
  before.add(s_.xyz[q], s_.xyz[p], s_.xyz[o]);
  const double limit = std::max(0.0, std::min({kLeanCos, lean(t), lean(t2)}));
  const std::array<Vec3, 3> x1{s_.xyz[r], s_.xyz[p], s_.xyz[o]}, x2{s_.xyz[r], s_.xyz[o], s_.xyz[q]};
  const std::array<Vec2, 3> w1{ur, up, uo}, w2{ur, uo, uq};
  if (!(lean(f, x1, w1) > limit) || !(lean(f, x2, w2) > limit)) return false;
  // The faces across the four outer edges stay; the new one is inside f.
  auto face_across = [&](int u, int v) {
    if ((u == r && v == o) || (u == o && v == r)) return f;
    const int skip = (u == r || v == r) ? t : t2;
    for (int x : node_tris_[u])
      if (x != skip && x != (skip == t ? t2 : t) && !dead_[x] && corner(x, v) < 3) return s_.tri_face[x];
    return -1;
  };
  if (thin_ear(f, {r, p, o}, face_across) || thin_ear(f, {r, o, q}, face_across)) return false;
  after.add(x1[0], x1[1], x1[2]);
  after.add(x2[0], x2[1], x2[2]);
  if (!apply) return true;
  s_.tris[t] = {r, p, o};
  s_.tri_uv[t] = w1;
  s_.tris[t2] = {r, o, q};
  s_.tri_uv[t2] = w2;
  node_tris_[r].push_back(t2);
  node_tris_[o].push_back(t);
  drop_tri(p, t2);
  drop_tri(q, t);
  flipped_other_ = t2;
  return true;
}

bool Cleaner::pinch(int t, bool apply, Shape& before, Shape& after) {
  Across x;
  if (!across_largest(t, x) || !(x.angle > 90) || faces(x.r).size() < 2 || s_.tri_face[x.t2] == s_.tri_face[t])
    return false;
  const int r = x.r, p = x.p, q = x.q, t2 = x.t2, o = x.o, f2 = s_.tri_face[t2];
  const Vec2 up = s_.tri_uv[t2][corner(t2, p)], uq = s_.tri_uv[t2][corner(t2, q)], uo = s_.tri_uv[t2][corner(t2, o)];
  Vec2 ur;
  if (!uv_in(r, f2, 0.5 * (up + uq), ur)) return false;
  before.add(s_.xyz[r], s_.xyz[p], s_.xyz[q]);
  before.add(s_.xyz[q], s_.xyz[p], s_.xyz[o]);
  const double limit = std::max(0.0, std::min({kLeanCos, lean(t2)}));
  const std::array<Vec3, 3> x1{s_.xyz[q], s_.xyz[r], s_.xyz[o]}, x2{s_.xyz[r], s_.xyz[p], s_.xyz[o]};
  const std::array<Vec2, 3> w1{uq, ur, uo}, w2{ur, up, uo};
  if (!(lean(f2, x1, w1) > limit) || !(lean(f2, x2, w2) > limit)) return false;
  // Across (q, r) and (r, p): t's neighbours; across (p, o), (o, q): t2's.
  auto face_across = [&](int u, int v) {
    if ((u == r && v == o) || (u == o && v == r)) return f2;
    for (int x : node_tris_[u])
      if (x != t && x != t2 && !dead_[x] && corner(x, v) < 3) return s_.tri_face[x];
    return -1;
  };
  if (thin_ear(f2, {q, r, o}, face_across) || thin_ear(f2, {r, p, o}, face_across)) return false;
  after.add(x1[0], x1[1], x1[2]);
  after.add(x2[0], x2[1], x2[2]);
  if (!apply) return true;
  dead_[t] = 1;
  s_.tris[t2] = {q, r, o};
  s_.tri_uv[t2] = w1;
  s_.tris.push_back({r, p, o});
  s_.tri_uv.push_back(w2);
  s_.tri_face.push_back(f2);
  dead_.push_back(0);
  const int t3 = static_cast<int>(s_.tris.size()) - 1;
  node_tris_[r].push_back(t2);
  node_tris_[r].push_back(t3);
  node_tris_[p].push_back(t3);
  node_tris_[o].push_back(t3);
  drop_tri(p, t2);
  flipped_other_ = t2;
  return true;
}

}  // namespace sizemesh::junction_slivers_detail
