// Curve nodes beside the junction moved or added to its sizes (space_curve_nodes), found on the curve itself.
#include "mesher/curve_node_spacing.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>

#include "background/background_mesh.h"
#include "mesher/junction_size.h"

namespace sizemesh::cut_faces_detail {
namespace {

// The parameter of curve c nearest x: the nearest of a few samples, then
// Newton on (C(t) - x) . C'(t) = 0 within the curve's range.
bool nearest_on_curve(const Geometry& g, int c, const Vec3& x, double& t) {
  double t0, t1;
  g.curve_range(c, t0, t1);
  if (!(t1 > t0)) return false;
  constexpr int kSamples = 64;
  double best = HUGE_VAL;
  for (int k = 0; k <= kSamples; ++k) {
    const double s = t0 + (t1 - t0) * k / kSamples;
    const double d = (g.eval_curve(c, s) - x).squaredNorm();
    if (d < best) best = d, t = s;
  }
  for (int it = 0; it < 20; ++it) {
    const Vec3 d = g.eval_curve(c, t) - x, tan = g.curve_tangent(c, t);
    const double tt = tan.squaredNorm();
    if (!(tt > 0)) break;
    const double step = d.dot(tan) / tt;
    t = std::clamp(t - step, t0, t1);
    if (std::abs(step) <= 1e-12 * (t1 - t0)) break;
  }
  return std::isfinite(t);
}

}  // namespace

bool space_curve_nodes(SurfaceMesh& s, const Geometry& g, const SizeField& h,
                       const std::vector<double>& size_slope, const std::vector<std::array<int, 2>>& junction) {
  bool changed = false;
  std::vector<char> on_junction(s.xyz.size(), 0);
  std::unordered_map<int, std::vector<int>> junction_next;
  for (const auto& [a, b] : junction) {
    on_junction[a] = on_junction[b] = 1;
    junction_next[a].push_back(b);
    junction_next[b].push_back(a);
  }
  std::vector<std::vector<int>> node_faces(s.xyz.size()), node_tris(s.xyz.size());
  std::unordered_map<uint64_t, std::vector<int>> edge_tris;
  for (size_t t = 0; t < s.tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = s.tris[t][k], f = s.tri_face[t];
      node_tris[a].push_back(static_cast<int>(t));
      if (std::find(node_faces[a].begin(), node_faces[a].end(), f) == node_faces[a].end()) node_faces[a].push_back(f);
      edge_tris[edge_key(a, s.tris[t][(k + 1) % 3])].push_back(static_cast<int>(t));
    }
  auto corner_of = [&](int t, int n) {
    return static_cast<int>(std::find(s.tris[t].begin(), s.tris[t].end(), n) - s.tris[t].begin());
  };
  // Neighbours of a along edges between two faces (the face boundaries through a).
  auto boundary_neighbours = [&](int a) {
    std::vector<int> out;
    for (int t : node_tris[a])
      for (int b : s.tris[t]) {
        if (b == a || std::find(out.begin(), out.end(), b) != out.end()) continue;
        const auto& tris = edge_tris[edge_key(a, b)];
        if (tris.size() == 2 && s.tri_face[tris[0]] != s.tri_face[tris[1]]) out.push_back(b);
      }
    return out;
  };
  // The point of `curve` nearest x, from the curve itself: snap() onto its
  // two faces does not converge where they meet tangent (a leading edge
  // split into upper and lower skins).
  auto on_curve = [&](int curve, const Vec3& x, Vec3& p) {
    double t = 0;
    try {
      if (!nearest_on_curve(g, curve, x, t)) return false;
      p = g.eval_curve(curve, t);
    } catch (const EvaluationError&) {
      return false;
    }
    return std::isfinite(p.x());
  };
  struct Split {
    int c, a, curve;
    std::vector<Vec3> x;  // new nodes from c to a
  };
  std::vector<Split> splits;
  std::set<int> split_tris;
  // The nodes that split the segment from node `from` to node `to` of
  // `curve` into `pieces` of equal integral of 1/h (Eq. 1a-1b), `integral`
  // being its running value over equal steps from `from`: each put on the
  // curve nearest its place along the chord. False when one is not within a
  // quarter of the segment of that place.
  auto place_on_curve = [&](int from, int to, int curve, const std::vector<double>& integral, int pieces,
                            std::vector<Vec3>& out) {
    const int steps = static_cast<int>(integral.size()) - 1;
    const double length = (s.xyz[to] - s.xyz[from]).norm();
    int step = 0;
    for (int i = 1; i < pieces; ++i) {
      const double at = integral.back() * i / pieces;
      while (step + 1 < steps && integral[step + 1] < at) ++step;
      const double span = integral[step + 1] - integral[step];
      const double d = length * (step + (span > 0 ? (at - integral[step]) / span : 0.0)) / steps;
      Vec3 x;
      const Vec3 target = s.xyz[from] + (s.xyz[to] - s.xyz[from]) * (d / length);
      if (!on_curve(curve, target, x) || !((x - target).norm() < 0.25 * length)) return false;
      out.push_back(x);
    }
    return true;
  };
  for (size_t c = 0; c < s.xyz.size(); ++c) {
    if (!on_junction[c] || s.node_dim[c] != 2 || node_faces[c].size() < 3) continue;
    for (int a : boundary_neighbours(static_cast<int>(c))) {
      if (s.node_dim[a] != 1 || on_junction[a]) continue;
      bool inside = true;
      for (int f : node_faces[a])
        inside = inside && std::find(node_faces[c].begin(), node_faces[c].end(), f) != node_faces[c].end();
      const std::vector<int> along = boundary_neighbours(a);
      if (!inside || along.size() != 2) continue;
      const int p = along[0] == static_cast<int>(c) ? along[1] : along[0], curve = s.node_entity[a];
      const double stub = (s.xyz[a] - s.xyz[c]).norm(), other = (s.xyz[p] - s.xyz[a]).norm();
      const auto& beside = edge_tris[edge_key(static_cast<int>(c), a)];
      if (stub < other / 3) {
        Vec3 x;
        const Vec3 target = 0.5 * (s.xyz[p] + s.xyz[c]);
        if (!on_curve(curve, target, x) || !((x - target).norm() < 0.25 * other)) continue;
        std::map<int, Vec2> uv;  // per face of a
        bool projected = true;
        for (int t : node_tris[a]) {
          const int f = s.tri_face[t];
          if (uv.count(f)) continue;
          Vec2 w = s.tri_uv[t][corner_of(t, a)];
          projected = projected && g.project_to_face(f, x, w);
          uv[f] = w;
        }
        if (!projected) continue;
        s.xyz[a] = x;
        for (int t : node_tris[a]) {
          const int k = corner_of(t, a);
          s.tri_uv[t][k] = unwrap_uv(g, s.tri_face[t], uv[s.tri_face[t]], s.tri_uv[t][k]);
        }
        changed = true;
        continue;
      }
      // Sizes along the segment: at the corner the finest of its faces (the
      // junction is meshed to the finer component), at a the finer of its
      // two, between them linear but grown from the corner's at no more than
      // the gradient bound (Eq. 12); the segment split by the integral of 1/h
      // (Eq. 1a-1b, as a CAD curve).
      double hc = HUGE_VAL, ha = HUGE_VAL, slope = 0;  // slope 0: no bound known
      for (int t : node_tris[c]) {
        int hint = -1;
        hc = std::min(hc, h.at(s.tri_face[t], s.tri_uv[t][corner_of(t, static_cast<int>(c))], hint));
      }
      for (int t : beside) {
        int hint = -1;
        ha = std::min(ha, h.at(s.tri_face[t], s.tri_uv[t][corner_of(t, a)], hint));
        const int f = s.tri_face[t];
        if (f < static_cast<int>(size_slope.size()) && size_slope[f] > 0)
          slope = slope > 0 ? std::min(slope, size_slope[f]) : size_slope[f];
      }
      if (!(hc > 0) || !(ha > 0) || !std::isfinite(hc) || !std::isfinite(ha)) continue;
      constexpr int kSteps = 64;
      std::vector<double> integral(kSteps + 1, 0.0);
      auto size_at = [&](double d) {
        const double linear = hc + (ha - hc) * d / stub;
        return slope > 0 ? std::min(linear, hc + slope * d) : linear;
      };
      for (int i = 1; i <= kSteps; ++i) {
        const double d0 = stub * (i - 1) / kSteps, d1 = stub * i / kSteps;
        integral[i] = integral[i - 1] + (d1 - d0) * 0.5 * (1 / size_at(d0) + 1 / size_at(d1));
      }
      const int pieces = std::min(32, static_cast<int>(std::lround(integral.back())));
      if (pieces < 2 || !(stub > 1.5 * size_at(0.5 * stub))) continue;
      // Not in a narrow wedge between the curve and the junction: its
      // triangles span it from side to side, and finer nodes on one side
      // only make them thinner.
      bool wedge = false;
      const Vec3 along_curve = (s.xyz[a] - s.xyz[c]).normalized();
      for (int j : junction_next[static_cast<int>(c)])
        wedge = wedge || along_curve.dot((s.xyz[j] - s.xyz[c]).normalized()) > std::cos(15.0 * kPi / 180.0);
      if (wedge) continue;
      if (beside.size() != 2 || split_tris.count(beside[0]) || split_tris.count(beside[1])) continue;
      Split sp{static_cast<int>(c), a, curve, {}};
      if (!place_on_curve(static_cast<int>(c), a, curve, integral, pieces, sp.x)) continue;
      split_tris.insert(beside.begin(), beside.end());
      splits.push_back(std::move(sp));
    }
  }
  // Curve segments inside the faces the junction cuts, longer than 1.5
  // times the size wanted along them once the junction's sizes grow into
  // those faces (Eq. 12 from every junction node, as the faces are meshed
  // again): a segment keeps its component's coarser spacing, and the
  // region between it and a finer junction running beside it is a row of
  // caps. Split on the curve by the integral of 1/h, as above.
  std::set<int> cut;
  for (const auto& [a, b] : junction)
    for (int t : edge_tris[edge_key(a, b)]) cut.insert(s.tri_face[t]);
  JunctionGradedSize graded(g, h, size_slope);
  for (size_t n = 0; n < s.xyz.size(); ++n) {
    if (!on_junction[n]) continue;
    double size = HUGE_VAL;
    for (int t : node_tris[n]) {
      int hint = -1;
      size = std::min(size, h.at(s.tri_face[t], s.tri_uv[t][corner_of(t, static_cast<int>(n))], hint));
    }
    for (int f : node_faces[n]) graded.add(f, s.xyz[n], size);
  }
  graded.finish();
  for (const auto& [key, beside] : edge_tris) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    if (s.node_dim[a] > 1 || s.node_dim[b] > 1 || on_junction[a] || on_junction[b] || beside.size() != 2) continue;
    if (s.node_dim[a] == 0 && s.node_dim[b] == 0) continue;
    if (s.node_dim[a] == 1 && s.node_dim[b] == 1 && s.node_entity[a] != s.node_entity[b]) continue;
    if (!cut.count(s.tri_face[beside[0]]) || !cut.count(s.tri_face[beside[1]])) continue;
    if (split_tris.count(beside[0]) || split_tris.count(beside[1])) continue;
    const int curve = s.node_dim[a] == 1 ? s.node_entity[a] : s.node_entity[b];
    const double length = (s.xyz[b] - s.xyz[a]).norm();
    // Sizes along the segment, the finer of its two faces'.
    constexpr int kSteps = 16;
    std::array<double, kSteps + 1> size{};
    bool sized = true;
    for (int i = 0; i <= kSteps && sized; ++i) {
      size[i] = HUGE_VAL;
      for (int t : beside) {
        const Vec2 ua = s.tri_uv[t][corner_of(t, a)], ub = s.tri_uv[t][corner_of(t, b)];
        int hint = -1;
        size[i] = std::min(size[i], graded.at(s.tri_face[t], ua + (ub - ua) * (double(i) / kSteps), hint));
      }
      sized = size[i] > 0 && std::isfinite(size[i]);
    }
    if (!sized || !(length > 1.5 * size[kSteps / 2])) continue;
    std::vector<double> integral(kSteps + 1, 0.0);
    for (int i = 1; i <= kSteps; ++i)
      integral[i] = integral[i - 1] + length / kSteps * 0.5 * (1 / size[i - 1] + 1 / size[i]);
    const int pieces = std::min(32, static_cast<int>(std::lround(integral.back())));
    if (pieces < 2) continue;
    Split sp{a, b, curve, {}};
    if (!place_on_curve(a, b, curve, integral, pieces, sp.x)) continue;
    split_tris.insert(beside.begin(), beside.end());
    splits.push_back(std::move(sp));
  }
  // Each split: the new nodes, and the two triangles beside the segment
  // replaced by fans to their third corner.
  std::vector<char> dropped(s.tris.size(), 0);
  const size_t old_tris = s.tris.size();
  for (const Split& sp : splits) {
    const auto beside = edge_tris[edge_key(sp.c, sp.a)];
    // uv along the segment in each face beside it, by projection from the straight line.
    std::vector<std::vector<Vec2>> w(beside.size());
    bool projected = true;
    for (size_t j = 0; j < beside.size() && projected; ++j) {
      const int t = beside[j], f = s.tri_face[t];
      const Vec2 uc = s.tri_uv[t][corner_of(t, sp.c)], ua = s.tri_uv[t][corner_of(t, sp.a)];
      w[j].push_back(uc);
      for (size_t i = 0; i < sp.x.size() && projected; ++i) {
        const double at = double(i + 1) / (sp.x.size() + 1);
        const Vec2 line = (1 - at) * uc + at * ua;
        Vec2 guess = line;
        projected = g.project_to_face(f, sp.x[i], guess);
        w[j].push_back(unwrap_uv(g, f, guess, line));
      }
      w[j].push_back(ua);
    }
    if (!projected) continue;
    std::vector<int> ids{sp.c};
    for (const Vec3& x : sp.x) {
      ids.push_back(static_cast<int>(s.xyz.size()));
      s.xyz.push_back(x);
      s.node_dim.push_back(1);
      s.node_entity.push_back(sp.curve);
    }
    ids.push_back(sp.a);
    for (size_t j = 0; j < beside.size(); ++j) {
      const int t = beside[j], f = s.tri_face[t];
      const auto tr = s.tris[t];
      const auto uv = s.tri_uv[t];
      const int kc = corner_of(t, sp.c), ka = corner_of(t, sp.a), ko = 3 - kc - ka;
      const bool forward = (kc + 1) % 3 == ka;  // the triangle runs c -> a
      dropped[t] = 1;
      for (size_t i = 0; i + 1 < ids.size(); ++i) {
        if (forward) {
          s.tris.push_back({ids[i], ids[i + 1], tr[ko]});
          s.tri_uv.push_back({w[j][i], w[j][i + 1], uv[ko]});
        } else {
          s.tris.push_back({ids[i + 1], ids[i], tr[ko]});
          s.tri_uv.push_back({w[j][i + 1], w[j][i], uv[ko]});
        }
        s.tri_face.push_back(f);
      }
    }
    changed = true;
  }
  if (splits.empty()) return changed;
  size_t out = 0;
  for (size_t t = 0; t < s.tris.size(); ++t) {
    if (t < old_tris && dropped[t]) continue;
    s.tris[out] = s.tris[t];
    s.tri_face[out] = s.tri_face[t];
    s.tri_uv[out] = s.tri_uv[t];
    ++out;
  }
  s.tris.resize(out);
  s.tri_face.resize(out);
  s.tri_uv.resize(out);
  return changed;
}

}  // namespace sizemesh::cut_faces_detail
