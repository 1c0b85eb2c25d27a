#include "sizing/proximity_size.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "sizing/curvature_size.h"
#include "sizing/size_map.h"
#include "core/triangle_bvh.h"

namespace sizemesh {

namespace {
// Face widths and curve lengths under this are below the deviation bound's
// accuracy (0 without a bound: every feature counts).
double below_accuracy(const SizingParams& p) { return 2 * p.deviation; }

double face_mu(const SizingParams& p, int face) {
  auto it = p.face_mu_d.find(face);
  return it == p.face_mu_d.end() ? p.mu_d : it->second;
}

// With a deviation bound delta, elements across a face of width w at vertex v:
// one half where the face is flat enough there that a chord across all of it
// stays within delta (its deviation size, the chord of height delta, is at
// least w). More elements across would not bring the mesh closer to the
// surface; one row of triangles spans the face, each twice as long as the face
// is wide (about right-angled and isosceles, its smallest angle near 45
// degrees), so the size the face hands on to its neighbours, and the
// gradation spreads, is 2 w rather than w. A mu_d under one half asks for
// even fewer and is kept, so sizes never shrink as mu_d falls. Elsewhere (and
// without a bound, or where the curvature cannot be evaluated) mu_d, the
// paper's count.
double elements_across(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p, int face, int v,
                       double w) {
  const double mu = face_mu(p, face);
  if (!(p.deviation > 0) || !(mu > 0.5)) return mu;
  for (int u = bg.use_start[v]; u < bg.use_start[v + 1]; ++u)
    if (bg.use_face[u] == face)  // NaN (curvature unknown) compares false: mu_d
      return face_deviation_size(g, face, bg.patches[face - 1].uv[bg.use_local[u]], p.deviation) >= w ? 0.5 : mu;
  return mu;
}

// A patch's boundary edges (local vertices a -> b, the patch's inside on the
// left): on the composite face's border, and on crossed curves (portals into
// the next face of the same composite).
struct BEdge {
  int a, b, curve;
};
struct PatchBorder {
  std::vector<BEdge> border, portal;
  std::vector<char> seam;  // per border edge: a seam or pole edge, no border
};

PatchBorder patch_border(const BackgroundMesh& bg, const FacePatch& patch, const SizingParams& p,
                         const std::unordered_map<uint64_t, int>& edge_of) {
  PatchBorder out;
  std::unordered_map<uint64_t, int> seen;  // global pair -> count among boundary edges
  for (size_t t = 0; t < patch.tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      if (patch.adj[t][k] >= 0) continue;
      const int a = patch.tris[t][(k + 1) % 3], b = patch.tris[t][(k + 2) % 3];
      const int ga = patch.vertex[a], gb = patch.vertex[b];
      if (ga == gb) continue;  // collapsed onto a pole
      auto it = edge_of.find(edge_key(ga, gb));
      const int curve = it == edge_of.end() ? 0 : bg.edge_curve[it->second];
      if (p.crossed(curve)) {
        out.portal.push_back({a, b, curve});
        continue;
      }
      out.border.push_back({a, b, curve});
      ++seen[edge_key(ga, gb)];
    }
  out.seam.resize(out.border.size());
  for (size_t i = 0; i < out.border.size(); ++i)
    out.seam[i] = seen[edge_key(patch.vertex[out.border[i].a], patch.vertex[out.border[i].b])] > 1;
  return out;
}

// Direction in uv, at a surface point with derivatives s, of the space
// vector `d` projected on the tangent plane; false where s is singular.
bool uv_direction(const SurfaceD1& s, const Vec3& d, Vec2& dir) {
  Eigen::Matrix2d jtj;
  jtj << s.du.dot(s.du), s.du.dot(s.dv), s.du.dot(s.dv), s.dv.dot(s.dv);
  if (!(std::abs(jtj.determinant()) > 0)) return false;
  dir = jtj.inverse() * Vec2(s.du.dot(d), s.dv.dot(d));
  return dir.norm() > 0;
}

// Where the ray o + s dir (s > 0) in uv crosses the edge p -> p + q: s and the
// edge's parameter r in [0, 1]; false when it does not.
bool ray_cross(const Vec2& o, const Vec2& dir, const Vec2& p, const Vec2& q, double& sray, double& r) {
  const double det = dir.x() * (-q.y()) - dir.y() * (-q.x());
  if (std::abs(det) < 1e-300) return false;
  const Vec2 w = p - o;
  sray = (w.x() * (-q.y()) - w.y() * (-q.x())) / det;
  r = (dir.x() * w.y() - dir.y() * w.x()) / det;
  return sray > 0 && r >= 0 && r <= 1;
}

// Length over face `face` of the straight uv segment a -> b (a polyline of
// a few surface points): the width crossed on one face of a composite.
double length_over(const Geometry& g, int face, const Vec2& a, const Vec2& b, const Vec3& xa, const Vec3& xb) {
  constexpr int kSteps = 6;
  double length = 0;
  Vec3 last = xa;
  for (int i = 1; i < kSteps; ++i) {
    const Vec3 x = g.eval_face(face, a + (b - a) * (static_cast<double>(i) / kSteps)).p;
    length += (x - last).norm();
    last = x;
  }
  return length + (xb - last).norm();
}

// The width of each face across itself at each of its boundary vertices:
// from the vertex, rays in uv along the inward normals (perpendicular in
// space to the adjacent boundary edges, in the tangent plane) to the first
// boundary edge they cross; the width is the distance in space to that
// crossing. Seams and pole edges are no boundary. A crossing on a curve that
// meets the vertex's own (other) curve at a point nearer than 10 widths is a
// corner closing, not a thin region, and is passed over. A ray that reaches a
// crossed curve first goes on into the next face of the composite (its
// direction carried in space across the curve, a few faces at most) and the
// width is its length over the faces crossed: a composite face of several
// narrow faces (a blunt trailing edge's base, split at its middle) is as
// narrow as it is. Results: (global vertex, width).
void face_widths(const Geometry& g, const BackgroundMesh& bg, size_t pi, const std::vector<PatchBorder>& borders,
                 const std::unordered_map<uint64_t, std::vector<std::pair<int, int>>>& portals,
                 std::vector<std::pair<int, double>>& out) {
  constexpr int kHops = 4;  // faces a ray crosses into at most
  const FacePatch& patch = bg.patches[pi];
  const std::vector<BEdge>& border = borders[pi].border;
  const std::vector<char>& seam = borders[pi].seam;
  // B-rep points that end the curve a vertex lies on (or the point itself).
  auto ends = [&](int v, int curve, int out_pts[2]) {
    out_pts[0] = out_pts[1] = -1;
    if (bg.dim[v] == 0) out_pts[0] = bg.entity[v];
    else if (curve > 0) out_pts[0] = g.curve_start_point(curve), out_pts[1] = g.curve_end_point(curve);
  };
  // A border crossing that is a corner closing on x0's curve `curve` (own: its end points).
  auto corner = [&](const BEdge& h, int curve, const int* own, const Vec3& x0, double width) {
    bool c = false;
    for (int k = 0; k < 2; ++k)
      if (const int pt = own[k]; pt > 0 && h.curve > 0 && h.curve != curve &&
          (g.curve_start_point(h.curve) == pt || g.curve_end_point(h.curve) == pt))
        c |= (g.point_xyz(pt) - x0).norm() < 10 * width;
    return c;
  };
  // The nearest portal of patch `at` the ray crosses (skipping `skip`, a portal index): its index, s and r.
  auto first_portal = [&](size_t at, const Vec2& o, const Vec2& dir, int skip, double& s_best, double& r_best) {
    const FacePatch& pa = bg.patches[at];
    int best = -1;
    for (size_t j = 0; j < borders[at].portal.size(); ++j) {
      if (static_cast<int>(j) == skip) continue;
      const BEdge& h = borders[at].portal[j];
      double sray, r;
      if (ray_cross(o, dir, pa.uv[h.a], pa.uv[h.b] - pa.uv[h.a], sray, r) && sray < s_best)
        s_best = sray, r_best = r, best = static_cast<int>(j);
    }
    return best;
  };
  for (size_t i = 0; i < border.size(); ++i) {
    if (seam[i]) continue;
    const BEdge& e = border[i];
    const Vec2 mid = 0.5 * (patch.uv[e.a] + patch.uv[e.b]);
    const SurfaceD1 s = g.eval_face(patch.face, mid);
    const Vec3 along = bg.xyz[patch.vertex[e.b]] - bg.xyz[patch.vertex[e.a]];
    const Vec3 inward = s.du.cross(s.dv).cross(along);  // left of a -> b in uv, in space
    Vec2 dir;
    if (!(inward.norm() > 0) || !uv_direction(s, inward, dir)) continue;
    for (int from : {e.a, e.b}) {
      const Vec2 o = patch.uv[from];
      const Vec3 xo = bg.xyz[patch.vertex[from]];
      int own[2];
      ends(patch.vertex[from], e.curve, own);
      double best = kNoLimit, best_s = kNoLimit;
      for (size_t j = 0; j < border.size(); ++j) {
        const BEdge& h = border[j];
        if (seam[j] || h.a == from || h.b == from) continue;
        double sray, r;
        if (!ray_cross(o, dir, patch.uv[h.a], patch.uv[h.b] - patch.uv[h.a], sray, r)) continue;
        const Vec3 hit = (1 - r) * bg.xyz[patch.vertex[h.a]] + r * bg.xyz[patch.vertex[h.b]];
        const double width = (hit - xo).norm();
        if (!(width < best) || corner(h, e.curve, own, xo, width)) continue;
        best = width, best_s = sray;
      }
      // Into the composite's next faces when a crossed curve comes first.
      double s_portal = best_s, r = 0;
      int k = first_portal(pi, o, dir, -1, s_portal, r);
      if (k >= 0) {
        best = kNoLimit;
        size_t at = pi;
        Vec2 uv_at = o, dir_at = dir;
        Vec3 x_at = xo;
        double walked = 0;
        for (int hop = 0; hop < kHops && k >= 0; ++hop) {
          const FacePatch& pa = bg.patches[at];
          const BEdge& h = borders[at].portal[k];
          const Vec2 uv_hit = (1 - r) * pa.uv[h.a] + r * pa.uv[h.b];
          const Vec3 x_hit = (1 - r) * bg.xyz[pa.vertex[h.a]] + r * bg.xyz[pa.vertex[h.b]];
          walked += length_over(g, pa.face, uv_at, uv_hit, x_at, x_hit);
          // The same edge seen from the other side.
          const int ga = pa.vertex[h.a], gb = pa.vertex[h.b];
          const auto it = portals.find(edge_key(ga, gb));
          if (it == portals.end()) break;
          int next = -1, next_k = -1;
          for (const auto& [q, j] : it->second)
            if (q != static_cast<int>(at) || j != k) next = q, next_k = j;
          if (next < 0) break;
          const FacePatch& pn = bg.patches[next];
          const BEdge& hn = borders[next].portal[next_k];
          const double rn = pn.vertex[hn.a] == ga ? r : 1 - r;
          const Vec2 uv_next = (1 - rn) * pn.uv[hn.a] + rn * pn.uv[hn.b];
          const SurfaceD1 sa = g.eval_face(pa.face, uv_hit), sn = g.eval_face(pn.face, uv_next);
          Vec2 dir_next;
          if (!uv_direction(sn, sa.du * dir_at.x() + sa.dv * dir_at.y(), dir_next)) break;
          at = next, uv_at = uv_next, dir_at = dir_next, x_at = x_hit;
          // The nearest border crossing in the next face, then its portals.
          double s_border = kNoLimit, r_border = 0;
          const BEdge* hit_border = nullptr;
          for (size_t j = 0; j < borders[at].border.size(); ++j) {
            const BEdge& hb = borders[at].border[j];
            double sray, rr;
            if (borders[at].seam[j] ||
                !ray_cross(uv_at, dir_at, pn.uv[hb.a], pn.uv[hb.b] - pn.uv[hb.a], sray, rr) || !(sray < s_border))
              continue;
            const Vec3 hit = (1 - rr) * bg.xyz[pn.vertex[hb.a]] + rr * bg.xyz[pn.vertex[hb.b]];
            if (corner(hb, e.curve, own, xo, walked + (hit - x_at).norm())) continue;
            s_border = sray, r_border = rr, hit_border = &hb;
          }
          s_portal = s_border;
          k = first_portal(at, uv_at, dir_at, next_k, s_portal, r);
          if (k < 0 && hit_border) {
            const Vec2 uv_end = (1 - r_border) * pn.uv[hit_border->a] + r_border * pn.uv[hit_border->b];
            const Vec3 x_end = (1 - r_border) * bg.xyz[pn.vertex[hit_border->a]] + r_border * bg.xyz[pn.vertex[hit_border->b]];
            best = walked + length_over(g, pn.face, uv_at, uv_end, x_at, x_end);
          }
        }
      }
      if (best < kNoLimit) out.emplace_back(patch.vertex[from], best);
    }
  }
}

}  // namespace

// h_d1 = d_s / mu_d: the paper's d_s = 2 A / l is a face's width when the face
// is a strip, and nothing like it for a plate with holes or a ragged border.
// Here d_s is that width measured locally, across the face from each boundary
// vertex (equal to 2 A / l on a strip); the smallest over a vertex's faces.
// Inner vertices get no face-proximity bound: gradation carries it inwards.
// With a deviation bound delta, a face narrower than 2 delta is a feature below
// the accuracy asked for (the whole strip lies within delta of one curve):
// its width sets no size, and it is spanned by elements as long as its
// neighbours' (thin triangles the report counts as forced by a narrow face).
// A wider face gets one row of elements twice its width long where it is flat
// enough for that (elements_across), mu_d where it is curved.
std::vector<double> face_proximity_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p) {
  const std::unordered_map<uint64_t, int> edge_of = bg.edge_index();
  std::vector<PatchBorder> borders(bg.patches.size());
  tbb::parallel_for(0, static_cast<int>(bg.patches.size()), [&](int i) {
    if (!bg.patches[i].tris.empty()) borders[i] = patch_border(bg, bg.patches[i], p, edge_of);
  });
  // Crossed-curve edges -> (patch, portal) of each side.
  std::unordered_map<uint64_t, std::vector<std::pair<int, int>>> portals;
  for (size_t i = 0; i < borders.size(); ++i)
    for (size_t j = 0; j < borders[i].portal.size(); ++j) {
      const BEdge& h = borders[i].portal[j];
      portals[edge_key(bg.patches[i].vertex[h.a], bg.patches[i].vertex[h.b])].emplace_back(static_cast<int>(i),
                                                                                           static_cast<int>(j));
    }
  std::vector<std::vector<std::pair<int, double>>> widths(bg.patches.size());
  tbb::parallel_for(0, static_cast<int>(bg.patches.size()), [&](int i) {
    if (!bg.patches[i].tris.empty()) face_widths(g, bg, i, borders, portals, widths[i]);
  });
  std::vector<double> h(bg.num_vertices(), kNoLimit);
  for (size_t i = 0; i < widths.size(); ++i)
    for (const auto& [v, w] : widths[i])
      if (!(w < below_accuracy(p)))
        h[v] = std::min(h[v], w / elements_across(g, bg, p, static_cast<int>(i) + 1, v, w));
  return h;
}

// h_d0: the length of the shortest curve through the vertex; with a deviation
// bound delta, curves shorter than 2 delta set none (as narrow faces above).
std::vector<double> curve_length_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p) {
  std::vector<double> h(bg.num_vertices(), kNoLimit);
  // A feature curve's length is its composite curve's; a virtual one sets none.
  const auto length = [&](int c) {
    return c >= 1 && c <= static_cast<int>(p.chain_length.size()) ? p.chain_length[c - 1] : g.curve_length(c);
  };
  for (int c = 1; c <= g.num_curves(); ++c) {
    const double len = length(c);
    if (p.crossed(c) || g.curve_degenerated(c) || !(len > 0) || len < below_accuracy(p)) continue;
    for (int pt : {g.curve_start_point(c), g.curve_end_point(c)})
      if (pt > 0) h[pt - 1] = std::min(h[pt - 1], len);
  }
  for (int v = 0; v < bg.num_vertices(); ++v)
    if (bg.dim[v] == 1 && !p.crossed(bg.entity[v])) {
      const double len = length(bg.entity[v]);
      if (len > 0 && !(len < below_accuracy(p))) h[v] = std::min(h[v], len);
    }
  return h;
}

GapSizes gap_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p, double max_gap, double touch) {
  const int nv = bg.num_vertices(), nt = bg.num_triangles();
  GapSizes h(nv);
  if (nt == 0) return h;
  const int fluid = g.fluid_side();
  const GapSide side = p.gap_side == GapSide::Auto ? (fluid != 0 ? GapSide::Fluid : GapSide::Both) : p.gap_side;
  // Ray directions along the normal: +1 crosses the fluid on a body, the
  // solid on a flow domain.
  const double to_fluid = fluid < 0 ? -1.0 : 1.0;
  std::vector<double> signs;
  if (side != GapSide::Solid) signs.push_back(to_fluid);   // through the fluid
  if (side != GapSide::Fluid) signs.push_back(-to_fluid);  // through the solid: its thickness
  // Unit normals of the background triangles, oriented as their faces (out
  // of the solid on a closed model).
  std::vector<Vec3> tri_n(nt);
  for (int t = 0; t < nt; ++t) {
    const auto& tr = bg.tris[t];
    const Vec3 n = (bg.xyz[tr[1]] - bg.xyz[tr[0]]).cross(bg.xyz[tr[2]] - bg.xyz[tr[0]]);
    const double len = n.norm();
    tri_n[t] = len > 0 ? Vec3(n / len) : Vec3::Zero();
  }
  // A closed model's outward normals tell the sides apart: the surface hit
  // must face back at the ray's start (its outward normal against the start's,
  // for a ray through the fluid or through the solid alike). Sheets have no
  // outside: any surface facing the start, either way round, counts.
  auto facing = [&](int t, const Vec3& n) {
    const double c = tri_n[t].dot(n);
    return fluid != 0 ? c < -0.5 : std::abs(c) > 0.5;
  };
  // Curves bounding each face, to tell a gap from the wedge at a shared curve.
  std::vector<std::vector<int>> face_curves(g.num_faces() + 1);
  for (int f = 1; f <= g.num_faces(); ++f) {
    for (const FaceLoop& loop : g.face_loops(f))
      for (const CurveUse& u : loop) face_curves[f].push_back(u.curve);
    std::sort(face_curves[f].begin(), face_curves[f].end());
  }
  std::vector<std::vector<int>> curve_vertices(g.num_curves() + 1);
  for (int v = 0; v < nv; ++v)
    if (bg.dim[v] == 1) curve_vertices[bg.entity[v]].push_back(v);
  for (int c = 1; c <= g.num_curves(); ++c)
    for (int pt : {g.curve_start_point(c), g.curve_end_point(c)})
      if (pt > 0) curve_vertices[c].push_back(pt - 1);

  TriangleBVH bvh(bg.xyz, bg.tris);
  tbb::parallel_for(0, nv, [&](int v) {
    const int u0 = bg.use_start[v], u1 = bg.use_start[v + 1];
    auto on_own_face = [&](int f) {
      for (int u = u0; u < u1; ++u)
        if (bg.use_face[u] == f) return true;
      return false;
    };
    // Distance from v to the nearest vertex of a curve shared by faces f and f_hit.
    auto distance_to_shared_curve = [&](int f, int f_hit) {
      double d = INFINITY;
      const auto& a = face_curves[f];
      const auto& b = face_curves[f_hit];
      for (int c : a)
        if (std::binary_search(b.begin(), b.end(), c))
          for (int w : curve_vertices[c]) d = std::min(d, (bg.xyz[w] - bg.xyz[v]).norm());
      return d;
    };
    // One pair of rays per face the vertex lies on, along that face's own normal.
    for (int u = u0; u < u1; ++u) {
      const int f = bg.use_face[u];
      const SurfaceD1 d = g.eval_face(f, bg.patches[f - 1].uv[bg.use_local[u]]);
      Vec3 n = d.du.cross(d.dv);
      if (!(n.norm() > 0)) continue;  // singular point of the parametrisation
      n.normalize();
      if (g.face_reversed(f)) n = -n;
      for (double sign : signs) {
        auto hit = bvh.ray(bg.xyz[v], sign * n, max_gap, [&](int t) {
          return facing(t, n) && !on_own_face(bg.tri_face[t]);
        });
        if (hit.tri < 0 || !(hit.t > touch)) continue;
        // A wedge closing at a curve shared with the hit face (a sharp trailing
        // edge) is not a gap: its thickness falls to zero at that curve. A gap
        // is at least ten times thinner than its distance to such a curve.
        if (distance_to_shared_curve(f, bg.tri_face[hit.tri]) < 10.0 * hit.t) continue;
        auto& out = sign == to_fluid ? h.fluid : h.solid;
        out[v] = std::min(out[v], hit.t / face_mu(p, f));
      }
    }
  });
  return h;
}

}  // namespace sizemesh
