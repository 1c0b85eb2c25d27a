#include "mesher/ops/split.h"

#include <algorithm>
#include <cmath>

#include "core/predicates.h"

namespace sizemesh::ops {
namespace {

constexpr double kSplitMinAngle = 20;  // degrees: a split makes no new thin triangle
// A chord too far off the surface breaks the accuracy asked for, a long edge
// only the size: a split for the first may leave an angle down to 15 degrees.
constexpr double kSplitMinAngleOffSurface = 15;

}  // namespace

std::vector<LongEdge> long_edges(const FaceMesh& fm, const FaceSurface& fs, const SplitBounds& bounds,
                                 const std::vector<std::array<int, 3>>& nbr) {
  const SizeField& sf = fs.size_field();
  const double deviation = bounds.deviation, max_turn = bounds.max_turn;
  // How far the point of the mesh at uv (xyz) lies off the surface there:
  // in all, and along the surface's normal alone (a chord's height, without
  // the drift along the surface of a parametrisation that is not uniform).
  auto off = [&](const Vec2& uv, const Vec3& xyz, bool normal = false) {
    try {
      const SurfaceSample s = fs.eval_shape(uv);
      return normal ? std::abs((s.p - xyz).dot(s.n)) : (s.p - xyz).norm();
    } catch (const EvaluationError&) {
      return 0.0;
    }
  };
  std::vector<LongEdge> longs;
  for (int t = 0; t < static_cast<int>(fm.tris.size()); ++t) {
    if (fm.pole_triangle(fm.tris[t])) continue;
    const auto& tr = fm.tris[t];
    int longest = -1;
    double longest_len = 0;
    for (int k = 0; k < 3; ++k) {
      const int t2 = nbr[t][k];
      if (t2 < 0 || fm.pole_triangle(fm.tris[t2])) continue;
      const int a = tr[k], b = tr[(k + 1) % 3];
      const double len = (fm.position(a) - fm.position(b)).norm();
      if (len > longest_len) {
        longest_len = len;
        longest = k;
      }
      if (t2 < t) continue;  // each edge once
      const double h = sf.size_along(fm.s[a].h, fm.s[b].h);
      const double by_length = sf.length_excess(len, h);
      double excess = 0;
      const bool turn = max_turn > 0 && sf.may_split_for_turn(len, h, bounds.h_floor);
      const Vec2 uv_mid = 0.5 * (fm.uv[a] + fm.uv[b]);
      const Vec3 mid = 0.5 * (fm.position(a) + fm.position(b));
      if (deviation > 0) excess = std::max(excess, off(uv_mid, mid) / deviation);
      if (turn) excess = std::max(excess, sf.turn_excess(off(uv_mid, mid, true), len, max_turn));
      if (std::max(excess, by_length) > 1) longs.push_back({std::max(excess, by_length), t, k, excess > by_length});
    }
    if (deviation > 0 && longest >= 0) {
      const double centre = off((fm.uv[tr[0]] + fm.uv[tr[1]] + fm.uv[tr[2]]) / 3.0,
                                (fm.position(tr[0]) + fm.position(tr[1]) + fm.position(tr[2])) / 3.0) /
                            deviation;
      if (centre > 1) longs.push_back({centre, t, longest, true});
    }
  }
  std::sort(longs.begin(), longs.end(), [](const LongEdge& x, const LongEdge& y) {
    return x.excess != y.excess ? x.excess > y.excess : x.t != y.t ? x.t < y.t : x.k < y.k;
  });
  return longs;
}

SplitCheck check_split(const FaceMesh& fm, FaceSurface& fs, const std::vector<std::array<int, 3>>& nbr,
                       const std::vector<char>& touched, const LongEdge& l) {
  const int t1 = l.t, t2 = nbr[t1][l.k];
  if (t2 < 0 || touched[t1] || touched[t2]) return {};
  const auto T1 = fm.tris[t1], T2 = fm.tris[t2];
  const int a = T1[l.k], b = T1[(l.k + 1) % 3], c = T1[(l.k + 2) % 3];
  const int j = reversed_edge(T2, a, b);
  if (j < 0) return {};
  const int d = T2[(j + 2) % 3];
  const Vec2 uv = fs.size_field().split_point(fm.uv[a], fm.uv[b]);
  SurfaceSample sm;
  try {
    sm = fs.eval(uv);
  } catch (const EvaluationError&) {
    return {};
  }
  const double angle_old = std::min(final_min_angle(fm, T1), final_min_angle(fm, T2));
  const std::array<Vec2, 4> u{fm.uv[a], fm.uv[b], fm.uv[c], fm.uv[d]};
  const std::array<const SurfaceSample*, 4> p{&fm.s[a], &fm.s[b], &fm.s[c], &fm.s[d]};
  const std::array<const Vec3*, 4> x{&fm.position(a), &fm.position(b), &fm.position(c), &fm.position(d)};
  // (a, m, c), (m, b, c), (b, m, d), (m, a, d): corners as indices into u / p, 4 for m.
  const int corners[4][3] = {{0, 4, 2}, {4, 1, 2}, {1, 4, 3}, {4, 0, 3}};
  const double floor = std::min(angle_old, l.off_surface ? kSplitMinAngleOffSurface : kSplitMinAngle);
  bool keep = true;
  for (const auto& cn : corners) {
    auto U = [&](int i) { return i == 4 ? uv : u[i]; };
    auto P = [&](int i) -> const SurfaceSample& { return i == 4 ? sm : *p[i]; };
    auto X = [&](int i) -> const Vec3& { return i == 4 ? sm.p : *x[i]; };
    keep = keep && shape(U(cn[0]), U(cn[1]), U(cn[2]), P(cn[0]), P(cn[1]), P(cn[2]), fs) >= 0 &&
           min_angle_deg(X(cn[0]), X(cn[1]), X(cn[2])) >= floor;
  }
  if (!keep) return {};
  return {true, t2, a, b, c, d, uv, sm};
}

void apply_split(FaceMesh& fm, std::vector<char>& touched, int t1, const SplitCheck& c) {
  const int t2 = c.t2;
  const int m = fm.add_node(c.uv, c.sm, -1);
  fm.tris[t1] = {c.a, m, c.c};
  fm.tris[t2] = {c.b, m, c.d};
  fm.tris.push_back({m, c.b, c.c});
  fm.tris.push_back({m, c.a, c.d});
  touched[t1] = touched[t2] = 1;
}

int split_long_edges(FaceMesh& fm, FaceSurface& fs, const SplitBounds& bounds,
                     const std::vector<std::array<int, 3>>& nbr) {
  const std::vector<LongEdge> longs = long_edges(fm, fs, bounds, nbr);
  std::vector<char> touched(fm.tris.size(), 0);
  int splits = 0;
  for (const LongEdge& l : longs) {
    const SplitCheck c = check_split(fm, fs, nbr, touched, l);
    if (!c.ok) continue;
    apply_split(fm, touched, l.t, c);
    ++splits;
  }
  return splits;
}

}  // namespace sizemesh::ops
