#include "sizing/proximity_size.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "sizing/size_map.h"
#include "sizing/triangle_bvh.h"

namespace sizemesh {

namespace {
double face_mu(const SizingParams& p, int face) {
  auto it = p.face_mu_d.find(face);
  return it == p.face_mu_d.end() ? p.mu_d : it->second;
}
}  // namespace

// h_d1 = (2 A / l) / mu_d per face, the smallest over the faces a vertex lies on.
std::vector<double> face_proximity_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p) {
  std::vector<double> per_face(g.num_faces() + 1, kNoLimit);
  for (int f = 1; f <= g.num_faces(); ++f) {
    const double l = g.face_boundary_length(f);
    if (l > 0) per_face[f] = 2.0 * g.face_area(f) / l / face_mu(p, f);
  }
  std::vector<double> h(bg.num_vertices(), kNoLimit);
  for (int v = 0; v < bg.num_vertices(); ++v)
    for (int u = bg.use_start[v]; u < bg.use_start[v + 1]; ++u) h[v] = std::min(h[v], per_face[bg.use_face[u]]);
  return h;
}

// h_d0: the length of the shortest curve through the vertex.
std::vector<double> curve_length_sizes(const Geometry& g, const BackgroundMesh& bg) {
  std::vector<double> h(bg.num_vertices(), kNoLimit);
  for (int c = 1; c <= g.num_curves(); ++c) {
    const double len = g.curve_length(c);
    if (g.curve_degenerated(c) || !(len > 0)) continue;
    for (int pt : {g.curve_start_point(c), g.curve_end_point(c)})
      if (pt > 0) h[pt - 1] = std::min(h[pt - 1], len);
  }
  for (int v = 0; v < bg.num_vertices(); ++v)
    if (bg.dim[v] == 1) {
      const double len = g.curve_length(bg.entity[v]);
      if (len > 0) h[v] = std::min(h[v], len);
    }
  return h;
}

std::vector<double> gap_sizes(const Geometry& g, const BackgroundMesh& bg, const SizingParams& p, double max_gap) {
  const int nv = bg.num_vertices(), nt = bg.num_triangles();
  std::vector<double> h(nv, kNoLimit);
  if (nt == 0) return h;
  // Oriented unit normals of the background triangles.
  std::vector<Vec3> tri_n(nt);
  for (int t = 0; t < nt; ++t) {
    const auto& tr = bg.tris[t];
    const Vec3 n = (bg.xyz[tr[1]] - bg.xyz[tr[0]]).cross(bg.xyz[tr[2]] - bg.xyz[tr[0]]);
    const double len = n.norm();
    tri_n[t] = len > 0 ? Vec3(n / len) : Vec3::Zero();
  }
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
      for (double sign : {1.0, -1.0}) {
        auto hit = bvh.ray(bg.xyz[v], sign * n, max_gap, [&](int t) {
          return tri_n[t].dot(n) < -0.5 && !on_own_face(bg.tri_face[t]);
        });
        if (hit.tri < 0 || !(hit.t > 0)) continue;
        // A wedge closing at a curve shared with the hit face (a sharp trailing
        // edge) is not a gap: its thickness falls to zero at that curve. A gap
        // is at least ten times thinner than its distance to such a curve.
        if (distance_to_shared_curve(f, bg.tri_face[hit.tri]) < 10.0 * hit.t) continue;
        h[v] = std::min(h[v], hit.t / face_mu(p, f));
      }
    }
  });
  return h;
}

}  // namespace sizemesh
