// Midpoint refinement of the classified background mesh: the background can
// be made finer where its piecewise-linear sizes are too coarse to carry the
// size map (see sizing/refine_background.h), without losing classification.
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "background/background_mesh.h"
#include "core/geometry.h"

namespace sizemesh {
namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Parameter of vertex v on curve c; `other` is the edge's other end (to pick
// the right end of a closed curve). NaN when v is not on c.
double curve_param(const BackgroundMesh& bg, const Geometry& g, int c, int v, int other) {
  if (bg.dim[v] == 1) return bg.entity[v] == c ? bg.curve_t[v] : std::numeric_limits<double>::quiet_NaN();
  double t0, t1;
  g.curve_range(c, t0, t1);
  const bool at_start = g.curve_start_point(c) == bg.entity[v], at_end = g.curve_end_point(c) == bg.entity[v];
  if (bg.dim[v] != 0 || (!at_start && !at_end)) return std::numeric_limits<double>::quiet_NaN();
  if (at_start && at_end) {  // closed curve: the end nearer to the other vertex
    const double to = bg.dim[other] == 1 ? bg.curve_t[other] : std::numeric_limits<double>::quiet_NaN();
    if (!std::isfinite(to)) return std::numeric_limits<double>::quiet_NaN();
    return std::abs(to - t0) <= std::abs(to - t1) ? t0 : t1;
  }
  return at_start ? t0 : t1;
}

// uv of curve c's parameter t on face f, from the parameter curve (the seam
// side whose image is nearest the chord midpoint `near`), shifted by whole
// periods towards `near`.
Vec2 pcurve_uv(const Geometry& g, int c, int f, double t, const Vec2& near) {
  Vec2 best(NAN, NAN);
  for (int side = 0; side < 2; ++side) {
    Vec2 uv;
    try {
      uv = g.eval_pcurve(c, f, side, t);
    } catch (const Error&) {
      continue;
    }
    const double period[2] = {g.face_period_u(f), g.face_period_v(f)};
    for (int k = 0; k < 2; ++k)
      if (period[k] > 0) uv[k] += period[k] * std::round((near[k] - uv[k]) / period[k]);
    if (!std::isfinite(best.x()) || (uv - near).norm() < (best - near).norm()) best = uv;
  }
  return best;
}

}  // namespace

int split_edges(BackgroundMesh& bg, const Geometry& g, const std::vector<int>& edges) {
  const int ne = static_cast<int>(bg.edges.size());
  std::vector<char> marked(ne, 0);
  for (int e : edges)
    if (e >= 0 && e < ne) marked[e] = 1;
  const std::unordered_map<uint64_t, int> edge_of = bg.edge_index();
  auto edge_id = [&](int a, int b) {
    auto it = edge_of.find(edge_key(a, b));
    return it == edge_of.end() ? -1 : it->second;
  };

  // Curve edges: the middle of the parameter range. Edges next to a pole's
  // collapsed triangles, and curve edges whose parameter-curve midpoint would
  // fold a triangle in uv, are left alone.
  std::vector<double> mid_t(ne, std::numeric_limits<double>::quiet_NaN());
  for (int e = 0; e < ne; ++e) {
    if (!marked[e] || !bg.edge_curve[e]) continue;
    const int c = bg.edge_curve[e], a = bg.edges[e][0], b = bg.edges[e][1];
    const double ta = curve_param(bg, g, c, a, b), tb = curve_param(bg, g, c, b, a);
    if (std::isfinite(ta) && std::isfinite(tb) && ta != tb) mid_t[e] = 0.5 * (ta + tb);
    else marked[e] = 0;
  }
  for (const FacePatch& patch : bg.patches)
    for (size_t t = 0; t < patch.tris.size(); ++t)
      if (patch.global_tri[t] < 0)
        for (int k = 0; k < 3; ++k) {
          const int e = edge_id(patch.vertex[patch.tris[t][k]], patch.vertex[patch.tris[t][(k + 1) % 3]]);
          if (e >= 0) marked[e] = 0;
        }
  for (const FacePatch& patch : bg.patches)
    for (size_t t = 0; t < patch.tris.size(); ++t) {
      if (patch.global_tri[t] < 0) continue;
      const auto& tr = patch.tris[t];
      for (int k = 0; k < 3; ++k) {
        const int la = tr[k], lb = tr[(k + 1) % 3], lo = tr[(k + 2) % 3];
        const int e = edge_id(patch.vertex[la], patch.vertex[lb]);
        if (e < 0 || !marked[e] || !bg.edge_curve[e]) continue;
        // The new uv must keep the triangles it makes counter-clockwise. Split
        // alone in its triangle (the others sides left whole), that is exact:
        // both halves (a, m, o) and (m, b, o) keep a tenth of the triangle's
        // area, which lets a flat triangle along a curve (a corner close to
        // the curve edge) be split where the curve's midpoint in uv is off
        // the chord by more than the triangle is high. With other sides split
        // too, the new uv must stay within a quarter of the height of the chord.
        const Vec2 &a = patch.uv[la], &b = patch.uv[lb], &o = patch.uv[lo];
        const Vec2 chord = b - a;
        const Vec2 m = pcurve_uv(g, bg.edge_curve[e], patch.face, mid_t[e], 0.5 * (a + b));
        const double height = cross(chord, o - a);  // > 0, counter-clockwise
        const int e1 = edge_id(patch.vertex[lb], patch.vertex[lo]), e2 = edge_id(patch.vertex[lo], patch.vertex[la]);
        const bool alone = (e1 < 0 || !marked[e1]) && (e2 < 0 || !marked[e2]);
        const bool keeps = alone ? cross(m - a, o - a) > 0.1 * height && cross(b - m, o - m) > 0.1 * height
                                 : std::abs(cross(chord, m - a)) < 0.25 * height;
        if (!std::isfinite(m.x()) || !keeps) marked[e] = 0;
      }
    }

  auto add_vertex = [&](const Vec3& p, int dim, int entity, double t) {
    bg.xyz.push_back(p);
    bg.dim.push_back(static_cast<int8_t>(dim));
    bg.entity.push_back(entity);
    bg.curve_t.push_back(t);
    return bg.num_vertices() - 1;
  };
  std::vector<int> curve_mid(ne, -1);
  int split = 0;
  bool any = false;
  for (int e = 0; e < ne; ++e) {
    if (!marked[e]) continue;
    any = true;
    if (!bg.edge_curve[e]) continue;  // counted per face below
    ++split;
    curve_mid[e] = add_vertex(g.eval_curve(bg.edge_curve[e], mid_t[e]), 1, bg.edge_curve[e], mid_t[e]);
  }
  if (!any) return 0;

  for (FacePatch& patch : bg.patches) {
    std::unordered_map<uint64_t, int> local_mid;  // local vertex pair -> new local vertex
    std::vector<std::array<int, 3>> tris;
    tris.reserve(patch.tris.size());
    bool touched = false;
    for (const auto& tr : patch.tris) {
      std::array<int, 3> mid = {-1, -1, -1};  // new vertex on side k (corner k to k+1)
      for (int k = 0; k < 3; ++k) {
        const int la = tr[k], lb = tr[(k + 1) % 3];
        const int e = edge_id(patch.vertex[la], patch.vertex[lb]);
        if (e < 0 || !marked[e]) continue;
        auto [it, fresh] = local_mid.emplace(edge_key(la, lb), static_cast<int>(patch.vertex.size()));
        if (fresh) {
          const Vec2 chord_mid = 0.5 * (patch.uv[la] + patch.uv[lb]);
          if (bg.edge_curve[e]) {
            patch.uv.push_back(pcurve_uv(g, bg.edge_curve[e], patch.face, mid_t[e], chord_mid));
            patch.vertex.push_back(curve_mid[e]);
          } else {
            ++split;
            patch.uv.push_back(chord_mid);
            patch.vertex.push_back(
                add_vertex(g.eval_face(patch.face, chord_mid).p, 2, patch.face, std::numeric_limits<double>::quiet_NaN()));
          }
        }
        mid[k] = it->second;
      }
      const int n = (mid[0] >= 0) + (mid[1] >= 0) + (mid[2] >= 0);
      touched |= n > 0;
      if (n == 0) {
        tris.push_back(tr);
      } else if (n == 1) {
        const int k = mid[0] >= 0 ? 0 : mid[1] >= 0 ? 1 : 2;
        const int a = tr[k], b = tr[(k + 1) % 3], o = tr[(k + 2) % 3], m = mid[k];
        tris.push_back({a, m, o});
        tris.push_back({m, b, o});
      } else if (n == 2) {
        const int j = mid[0] < 0 ? 0 : mid[1] < 0 ? 1 : 2;  // the side kept whole
        const int a = tr[j], b = tr[(j + 1) % 3], o = tr[(j + 2) % 3];
        const int m1 = mid[(j + 1) % 3], m2 = mid[(j + 2) % 3];  // on b-o and o-a
        tris.push_back({m1, o, m2});
        // The quad a, b, m1, m2 across its shorter diagonal in space.
        const auto& x = bg.xyz;
        if ((x[patch.vertex[a]] - x[patch.vertex[m1]]).norm() <= (x[patch.vertex[b]] - x[patch.vertex[m2]]).norm()) {
          tris.push_back({a, b, m1});
          tris.push_back({a, m1, m2});
        } else {
          tris.push_back({a, b, m2});
          tris.push_back({b, m1, m2});
        }
      } else {
        tris.push_back({tr[0], mid[0], mid[2]});
        tris.push_back({mid[0], tr[1], mid[1]});
        tris.push_back({mid[2], mid[1], tr[2]});
        tris.push_back({mid[0], mid[1], mid[2]});
      }
    }
    if (!touched) continue;
    patch.tris = std::move(tris);
    build_adjacency(patch);
  }

  std::vector<CurveEdge> curve_edges;
  for (int e = 0; e < ne; ++e) {
    if (!bg.edge_curve[e]) continue;
    const auto [a, b] = bg.edges[e];
    if (curve_mid[e] < 0) {
      curve_edges.push_back({{a, b}, bg.edge_curve[e]});
    } else {
      curve_edges.push_back({{a, curve_mid[e]}, bg.edge_curve[e]});
      curve_edges.push_back({{curve_mid[e], b}, bg.edge_curve[e]});
    }
  }
  assemble_background(bg, g, curve_edges);
  return split;
}

}  // namespace sizemesh
