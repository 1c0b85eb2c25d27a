#include "mesher/optimise.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>

#include "geometry/predicates.h"
#include "geometry/vertex_triangles.h"

namespace sizemesh {
namespace {

constexpr double kCosMin = 0.5;    // triangle normal against the surface normal
constexpr double kCosAgree = 0.90630778703665;  // cos 25 deg: corner normals that agree
constexpr double kSwapBelow = 0.8;  // only triangles worse than this look for a better diagonal

// Shape in space of (a, b, c) at the given corner samples; -1 when the triangle
// is folded in uv or turned away from the surface at a corner or at its uv
// centroid (the quality report's test for an inverted triangle).
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

// Triangle neighbours: nbr[t][k] is the triangle across edge (t[k], t[k+1]), -1 on the boundary.
std::vector<std::array<int, 3>> neighbours(const FaceMesh& fm) {
  struct Half {
    uint64_t key;
    int t, k;
  };
  std::vector<Half> half;
  half.reserve(fm.tris.size() * 3);
  for (int t = 0; t < static_cast<int>(fm.tris.size()); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = fm.tris[t][k], b = fm.tris[t][(k + 1) % 3];
      half.push_back({(uint64_t(uint32_t(std::min(a, b))) << 32) | uint32_t(std::max(a, b)), t, k});
    }
  std::sort(half.begin(), half.end(), [](const Half& x, const Half& y) {
    return x.key != y.key ? x.key < y.key : x.t < y.t;
  });
  std::vector<std::array<int, 3>> nbr(fm.tris.size(), {-1, -1, -1});
  for (size_t i = 0; i + 1 < half.size(); ++i)
    if (half[i].key == half[i + 1].key && (i + 2 >= half.size() || half[i + 2].key != half[i].key) &&
        (i == 0 || half[i - 1].key != half[i].key)) {
      nbr[half[i].t][half[i].k] = half[i + 1].t;
      nbr[half[i + 1].t][half[i + 1].k] = half[i].t;
    }
  return nbr;
}

void repoint(std::vector<std::array<int, 3>>& nbr, int t, int from, int to) {
  if (t < 0) return;
  for (int k = 0; k < 3; ++k)
    if (nbr[t][k] == from) nbr[t][k] = to;
}

// Where triangle T2 holds edge a -> b of its neighbour reversed: the j with
// T2[j] == b and T2[j + 1] == a (its third corner is T2[j + 2]); -1 if none.
int reversed_edge(const std::array<int, 3>& T2, int a, int b) {
  for (int j = 0; j < 3; ++j)
    if (T2[j] == b && T2[(j + 1) % 3] == a) return j;
  return -1;
}

// One sweep of diagonal swaps that raise the worse shape of the two triangles.
int swap_sweep(FaceMesh& fm, const FaceSurface& fs, std::vector<std::array<int, 3>>& nbr) {
  int swaps = 0;
  const int n = static_cast<int>(fm.tris.size());
  std::vector<double> q(n);
  for (int t = 0; t < n; ++t) q[t] = fm.pole_triangle(fm.tris[t]) ? 2.0 : shape(fm, fs, fm.tris[t]);
  for (int t1 = 0; t1 < n; ++t1) {
    if (fm.pole_triangle(fm.tris[t1]) || q[t1] > kSwapBelow) continue;
    for (int k = 0; k < 3; ++k) {
      const int t2 = nbr[t1][k];
      if (t2 < 0 || fm.pole_triangle(fm.tris[t2])) continue;
      const auto T1 = fm.tris[t1], T2 = fm.tris[t2];
      const int a = T1[k], b = T1[(k + 1) % 3], c = T1[(k + 2) % 3];
      const int j = reversed_edge(T2, a, b);
      if (j < 0) continue;
      const int d = T2[(j + 2) % 3];
      if (d == c) continue;
      const std::array<int, 3> n1{c, a, d}, n2{d, b, c};
      if (fm.pole_triangle(n1) || fm.pole_triangle(n2)) continue;
      const double q_old = std::min(q[t1], q[t2]);
      const double q1 = shape(fm, fs, n1), q2 = shape(fm, fs, n2);
      if (!(std::min(q1, q2) > q_old + 1e-6)) continue;
      q[t1] = q1;
      q[t2] = q2;
      const int o_ca = nbr[t1][(k + 2) % 3], o_bc = nbr[t1][(k + 1) % 3];
      const int o_ad = nbr[t2][(j + 1) % 3], o_db = nbr[t2][(j + 2) % 3];
      fm.tris[t1] = n1;  // edges c-a, a-d, d-c
      fm.tris[t2] = n2;  // edges d-b, b-c, c-d
      nbr[t1] = {o_ca, o_ad, t2};
      nbr[t2] = {o_db, o_bc, t1};
      repoint(nbr, o_ad, t2, t1);
      repoint(nbr, o_bc, t1, t2);
      ++swaps;
      break;  // t1 changed: move on
    }
  }
  return swaps;
}

// Triangles around every node: those of node i are tri_of[start[i] .. start[i+1]).
struct Balls {
  std::vector<int> start, tri_of;
  explicit Balls(const FaceMesh& fm) { vertex_triangles(fm.num_nodes(), fm.tris, start, tri_of); }
};

// Node i's triangles with i moved to (uv, s): whether they all stay valid,
// their worst shape, their smallest corner angle (degrees) and how many are
// under 12 degrees (pole triangles only need to stay counter-clockwise).
// `lenient`, per triangle of the ball: it already failed the shape's validity
// (the surface's normal turns more than 60 degrees within it) and need only
// stay counter-clockwise in uv and not turned against the surface at its
// centroid, the report's inverted test.
struct BallMeasure {
  bool valid = true;
  double shape = 2, angle = 180;
  int thin = 0;
  // Fewer thin triangles first, then a larger smallest angle.
  bool better_than(const BallMeasure& o, double by) const {
    return thin < o.thin || (thin == o.thin && angle > o.angle + by);
  }
};

BallMeasure measure_ball(const FaceMesh& fm, const FaceSurface& fs, const Balls& b, int i, const Vec2& uv,
                         const SurfaceSample& s, const std::vector<char>* lenient = nullptr) {
  BallMeasure m;
  for (int e = b.start[i]; e < b.start[i + 1] && m.valid; ++e) {
    const auto& tr = fm.tris[b.tri_of[e]];
    Vec2 u[3];
    const SurfaceSample* p[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = tr[k] == i ? uv : fm.uv[tr[k]];
      p[k] = tr[k] == i ? &s : &fm.s[tr[k]];
    }
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

// One sweep of smoothing: each inner node moves towards the mean of its
// neighbours in space (one Gauss-Newton step in uv), kept only if the worst
// shape around it does not get worse.
int smooth_sweep(FaceMesh& fm, const FaceSurface& fs) {
  const int n = fm.num_nodes();
  const Balls balls(fm);
  const std::vector<int>&start = balls.start, &tri_of = balls.tri_of;
  int moved = 0;
  for (int i = 0; i < n; ++i) {
    if (fm.boundary(i) || start[i] == start[i + 1]) continue;
    Vec3 target = Vec3::Zero();
    int cnt = 0;
    double old_q = 2;
    for (int e = start[i]; e < start[i + 1]; ++e) {
      const auto& tr = fm.tris[tri_of[e]];
      for (int v : tr)
        if (v != i) {
          target += fm.s[v].p;
          ++cnt;
        }
      if (!fm.pole_triangle(tr)) old_q = std::min(old_q, shape(fm, fs, tr));
    }
    target /= cnt;
    const SurfaceSample& si = fm.s[i];
    Eigen::Matrix<double, 3, 2> J;
    J.col(0) = si.du;
    J.col(1) = si.dv;
    const Eigen::Matrix2d JtJ = J.transpose() * J;
    if (!(std::abs(JtJ.determinant()) > 1e-300)) continue;
    const Vec2 step = JtJ.ldlt().solve(J.transpose() * (target - si.p));
    if (!std::isfinite(step.x()) || !std::isfinite(step.y())) continue;
    for (double f : {1.0, 0.5}) {
      const Vec2 uv = fm.uv[i] + f * step;
      SurfaceSample s;
      try {
        s = fs.eval_shape(uv);
      } catch (const EvaluationError&) {
        continue;  // outside what the surface can evaluate: stay
      }
      s.h = si.h;
      const BallMeasure moved_to = measure_ball(fm, fs, balls, i, uv, s);
      if (!moved_to.valid || moved_to.shape < old_q) continue;
      fm.uv[i] = uv;
      fm.s[i] = s;
      ++moved;
      break;
    }
  }
  return moved;
}

// Smallest angle of triangle t where its nodes lie in the assembled mesh
// (boundary nodes at their curve's xyz), in degrees.
double final_min_angle(const FaceMesh& fm, const std::array<int, 3>& t) {
  return min_angle_deg(fm.position(t[0]), fm.position(t[1]), fm.position(t[2]));
}

// One round of splits of edges inside the face that are too long: longer
// than kSplitAbove times the size wanted along them (the geometric mean of
// their ends' sizes), or, under a deviation bound d > 0, with their middle or
// (for the longest edge of a triangle) the triangle's centre further than d
// from the surface at the same uv, or, with max_turn > 0, over kTurnSplitAbove
// sizes long and turning along the surface by more than kTurnSlack max_turn
// (a chord of length l whose middle lies s off the surface turns by about
// 8 s / l). Where the front closed on a far node the surface lies furthest
// from the mesh: a chord's height grows with its square. Each edge gets a
// node at its uv midpoint and its two triangles become four, kept only if all
// four are valid and none has an angle below both 20 degrees (15 for a chord
// off the surface) and the smallest of the pair it replaces. Worst edges
// first, each triangle split once per round. nbr: the triangles' neighbours
// (neighbours()) on entry.
constexpr double kSplitAbove = 1.4;
constexpr double kSplitMinAngle = 20;  // degrees: a split makes no new thin triangle
// A chord too far off the surface breaks the accuracy asked for, a long edge
// only the size: a split for the first may leave an angle down to 15 degrees.
constexpr double kSplitMinAngleOffSurface = 15;
// An edge up to 1.4 curvature sizes long turns by 1.4 phi_c and cuts twice as
// deep as phi_c allows (height ~ length^2); 1.25 keeps it within 1.6 times.
// Edges under 1.1 sizes are left alone, and so are those a split would cut
// under h_min: there a small radius turns every edge by more than phi_c, and
// h_min is the user's word on how small to go.
constexpr double kTurnSlack = 1.25;
constexpr double kTurnSplitAbove = 1.1;
int split_long_edges(FaceMesh& fm, FaceSurface& fs, const SplitBounds& bounds,
                     const std::vector<std::array<int, 3>>& nbr) {
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
  struct Long {
    double excess;  // over 1: by length (in kSplitAbove sizes), off the surface (in d) or turning
    int t, k;
    bool off_surface;  // the excess is the distance from the surface (deviation or turn), not the length
  };
  std::vector<Long> longs;
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
      const double h = std::sqrt(fm.s[a].h * fm.s[b].h);
      const double by_length = h > 0 ? len / (kSplitAbove * h) : 0;
      double excess = 0;
      const bool turn = max_turn > 0 && h > 0 && len > kTurnSplitAbove * h && len >= 2 * bounds.h_floor;
      const Vec2 uv_mid = 0.5 * (fm.uv[a] + fm.uv[b]);
      const Vec3 mid = 0.5 * (fm.position(a) + fm.position(b));
      if (deviation > 0) excess = std::max(excess, off(uv_mid, mid) / deviation);
      if (turn) excess = std::max(excess, 8 * off(uv_mid, mid, true) / len / (kTurnSlack * max_turn));
      if (std::max(excess, by_length) > 1) longs.push_back({std::max(excess, by_length), t, k, excess > by_length});
    }
    if (deviation > 0 && longest >= 0) {
      const double centre = off((fm.uv[tr[0]] + fm.uv[tr[1]] + fm.uv[tr[2]]) / 3.0,
                                (fm.position(tr[0]) + fm.position(tr[1]) + fm.position(tr[2])) / 3.0) /
                            deviation;
      if (centre > 1) longs.push_back({centre, t, longest, true});
    }
  }
  std::sort(longs.begin(), longs.end(), [](const Long& x, const Long& y) {
    return x.excess != y.excess ? x.excess > y.excess : x.t != y.t ? x.t < y.t : x.k < y.k;
  });
  std::vector<char> touched(fm.tris.size(), 0);
  int splits = 0;
  for (const Long& l : longs) {
    const int t1 = l.t, t2 = nbr[t1][l.k];
    if (t2 < 0 || touched[t1] || touched[t2]) continue;
    const auto T1 = fm.tris[t1], T2 = fm.tris[t2];
    const int a = T1[l.k], b = T1[(l.k + 1) % 3], c = T1[(l.k + 2) % 3];
    const int j = reversed_edge(T2, a, b);
    if (j < 0) continue;
    const int d = T2[(j + 2) % 3];
    const Vec2 uv = 0.5 * (fm.uv[a] + fm.uv[b]);
    SurfaceSample sm;
    try {
      sm = fs.eval(uv);
    } catch (const EvaluationError&) {
      continue;
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
    if (!keep) continue;
    const int m = fm.add_node(uv, sm, -1);
    fm.tris[t1] = {a, m, c};
    fm.tris[t2] = {b, m, d};
    fm.tris.push_back({m, b, c});
    fm.tris.push_back({m, a, d});
    touched[t1] = touched[t2] = 1;
    ++splits;
  }
  return splits;
}

}  // namespace

int rescue_thin_triangles(FaceMesh& fm, const FaceSurface& fs) {
  constexpr double kRescueBelow = 15;
  const Balls balls(fm);
  int moved = 0;
  for (int i = 0; i < fm.num_nodes(); ++i) {
    if (fm.boundary(i) || balls.start[i] == balls.start[i + 1]) continue;
    double smallest = 180;  // from the positions alone, before any surface evaluation
    for (int e = balls.start[i]; e < balls.start[i + 1]; ++e) {
      const auto& t = fm.tris[balls.tri_of[e]];
      smallest = std::min(smallest, min_angle_deg(fm.s[t[0]].p, fm.s[t[1]].p, fm.s[t[2]].p));
    }
    if (!(smallest < kRescueBelow)) continue;
    Vec2 uv = fm.uv[i];
    SurfaceSample s = fm.s[i];
    std::vector<char> lenient;  // triangles that fail the shape's validity as they are
    for (int e = balls.start[i]; e < balls.start[i + 1]; ++e) {
      const auto& t = fm.tris[balls.tri_of[e]];
      lenient.push_back(!fm.pole_triangle(t) && shape(fm, fs, t) < 0);
    }
    BallMeasure best = measure_ball(fm, fs, balls, i, uv, s, &lenient);
    if (!best.valid || !(best.angle < kRescueBelow)) continue;
    const BallMeasure start_value = best;
    double step = 0;  // a third of the mean edge in uv
    for (int e = balls.start[i]; e < balls.start[i + 1]; ++e)
      for (int v : fm.tris[balls.tri_of[e]]) step += (fm.uv[v] - uv).norm();
    step /= 6.0 * (balls.start[i + 1] - balls.start[i]);
    for (int it = 0; it < 40 && step > 0; ++it) {
      bool improved = false;
      Vec2 best_uv = uv;
      SurfaceSample best_s = s;
      for (int d = 0; d < 8; ++d) {
        const double a = d * kPi / 4;
        const Vec2 trial = uv + step * Vec2(std::cos(a), std::sin(a));
        SurfaceSample ts;
        try {
          ts = fs.eval_shape(trial);
        } catch (const EvaluationError&) {
          continue;
        }
        ts.h = fm.s[i].h;
        const BallMeasure v = measure_ball(fm, fs, balls, i, trial, ts, &lenient);
        if (v.valid && v.better_than(best, 1e-9)) {
          best = v;
          best_uv = trial;
          best_s = ts;
          improved = true;
        }
      }
      if (improved) {
        uv = best_uv;
        s = best_s;
      } else {
        step *= 0.5;
      }
    }
    // Kept when it leaves fewer thin triangles, or none and a larger smallest
    // angle: a thin triangle traded for another one would only move it.
    if (best.thin < start_value.thin || (start_value.thin == 0 && best.better_than(start_value, 1e-6))) {
      fm.uv[i] = uv;
      fm.s[i] = s;
      ++moved;
    }
  }
  return moved;
}

// Collapses of the short edge of thin triangles (smallest angle under 12
// degrees): a needle whose short side joins an inner node to another node
// (a sliver the front left between two close nodes) loses that inner node,
// moved onto the other end. Kept only if every triangle of the removed
// node's ball stays valid, the link condition holds (the two ends share no
// neighbour but the corners opposite the edge, so no triangle is doubled),
// and the smallest angle of the ball grows. One collapse per neighbourhood;
// the removed nodes are dropped from fm afterwards.
int collapse_thin_triangles(FaceMesh& fm, const FaceSurface& fs) {
  constexpr double kThin = 12;
  const Balls balls(fm);
  const int nt = static_cast<int>(fm.tris.size());
  std::vector<char> dead(nt, 0), locked(fm.num_nodes(), 0), removed(fm.num_nodes(), 0);
  auto neighbours_of = [&](int v) {
    std::vector<int> n;
    for (int e = balls.start[v]; e < balls.start[v + 1]; ++e)
      for (int w : fm.tris[balls.tri_of[e]])
        if (w != v) n.push_back(w);
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
    return n;
  };
  int collapsed = 0;
  for (int t = 0; t < nt; ++t) {
    const auto tr = fm.tris[t];
    if (dead[t] || fm.pole_triangle(tr) || !(final_min_angle(fm, tr) < kThin)) continue;
    int k = 0;  // shortest side (tr[k], tr[k + 1])
    for (int j = 1; j < 3; ++j)
      if ((fm.position(tr[j]) - fm.position(tr[(j + 1) % 3])).squaredNorm() <
          (fm.position(tr[k]) - fm.position(tr[(k + 1) % 3])).squaredNorm())
        k = j;
    const int a = tr[k], b = tr[(k + 1) % 3];
    if (locked[a] || locked[b]) continue;
    // Try removing each inner end onto the other; keep the better result.
    double best_angle = -1;
    int best_r = -1;
    for (const auto& [r, keep] : {std::pair{a, b}, std::pair{b, a}}) {
      if (fm.boundary(r) || fm.pole[r]) continue;
      // Link condition: common neighbours are exactly the corners opposite the edge.
      const std::vector<int> nr = neighbours_of(r), nk = neighbours_of(keep);
      std::vector<int> common;
      std::set_intersection(nr.begin(), nr.end(), nk.begin(), nk.end(), std::back_inserter(common));
      int opposite = 0;
      double before = 180, after = 180;
      bool valid = true;
      for (int e = balls.start[r]; e < balls.start[r + 1] && valid; ++e) {
        const auto& q = fm.tris[balls.tri_of[e]];
        before = std::min(before, final_min_angle(fm, q));
        if (q[0] == keep || q[1] == keep || q[2] == keep) {
          ++opposite;
          continue;
        }
        std::array<int, 3> moved = q;
        for (int& v : moved)
          if (v == r) v = keep;
        if (fm.pole_triangle(moved)) {
          valid = orient(fm.uv[moved[0]], fm.uv[moved[1]], fm.uv[moved[2]]) > 0;
          continue;
        }
        valid = shape(fm, fs, moved) >= 0;
        after = std::min(after, final_min_angle(fm, moved));
      }
      if (!valid || opposite != 2 || static_cast<int>(common.size()) != 2 || !(after > before)) continue;
      if (after > best_angle) {
        best_angle = after;
        best_r = r;
      }
    }
    if (best_r < 0) continue;
    const int r = best_r, keep = best_r == a ? b : a;
    for (int e = balls.start[r]; e < balls.start[r + 1]; ++e) {
      const int q = balls.tri_of[e];
      auto& Q = fm.tris[q];
      if (Q[0] == keep || Q[1] == keep || Q[2] == keep) {
        dead[q] = 1;
        continue;
      }
      for (int& v : Q)
        if (v == r) v = keep;
    }
    removed[r] = 1;
    for (int v : neighbours_of(r)) locked[v] = 1;
    for (int v : neighbours_of(keep)) locked[v] = 1;
    locked[r] = locked[keep] = 1;
    ++collapsed;
  }
  if (collapsed == 0) return 0;
  std::vector<std::array<int, 3>> tris;
  tris.reserve(fm.tris.size());
  for (int t = 0; t < nt; ++t)
    if (!dead[t]) tris.push_back(fm.tris[t]);
  fm.tris = std::move(tris);
  fm.drop_nodes(removed);
  return collapsed;
}

void optimise(FaceMesh& fm, FaceSurface& fs, int passes, const SplitBounds& bounds) {
  if (passes <= 0 || fm.tris.empty()) return;
  std::vector<std::array<int, 3>> nbr = neighbours(fm);
  auto swaps = [&] {
    for (int k = 0; k < 4 && swap_sweep(fm, fs, nbr) > 0; ++k) {
    }
  };
  for (int p = 0; p < passes; ++p) {
    swaps();
    smooth_sweep(fm, fs);
  }
  swaps();
  // Edges still too long (or too far off the surface) after smoothing are split.
  for (int round = 0; round < 3 && split_long_edges(fm, fs, bounds, nbr) > 0; ++round) nbr = neighbours(fm);
  if (rescue_thin_triangles(fm, fs) > 0) swaps();
  if (collapse_thin_triangles(fm, fs) > 0) {
    nbr = neighbours(fm);
    swaps();
    smooth_sweep(fm, fs);
  }
}

}  // namespace sizemesh
