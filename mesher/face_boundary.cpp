#include "mesher/face_boundary.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace sizemesh {
namespace {

struct Entry {
  int global;
  Vec2 uv;
  bool pole;
};

double signed_area(const std::vector<Entry>& loop) {
  double a = 0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Vec2& p = loop[i].uv;
    const Vec2& q = loop[(i + 1) % loop.size()].uv;
    a += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * a;
}

// The nodes of one curve use in loop order, uv from the pcurve.
std::vector<Entry> use_entries(const Geometry& g, const CurveMesh& cm, int face, const CurveUse& u) {
  std::vector<Entry> part;
  if (g.curve_degenerated(u.curve)) {
    const int p = g.curve_start_point(u.curve);
    if (p <= 0) return part;
    double t0, t1;
    g.curve_range(u.curve, t0, t1);
    try {
      part.push_back({cm.point_node[p], g.eval_pcurve(u.curve, face, u.side, t0), true});
      part.push_back({cm.point_node[p], g.eval_pcurve(u.curve, face, u.side, t1), true});
    } catch (const EvaluationError&) {
      part.clear();  // no pcurve: the gap between its neighbours becomes the pole segment
    }
  } else {
    const CurveNodes& cn = cm.curves[u.curve];
    if (cn.node.empty())
      throw Error("curve " + std::to_string(u.curve) + " has no nodes");
    for (size_t i = 0; i < cn.t.size(); ++i)
      part.push_back({cn.node[i], g.eval_pcurve(u.curve, face, u.side, cn.t[i]), false});
  }
  if (u.reversed) std::reverse(part.begin(), part.end());
  return part;
}

}  // namespace

FaceMesh face_boundary(const Geometry& g, const CurveMesh& cm, FaceSurface& fs) {
  const int face = fs.face();
  std::vector<std::vector<Entry>> loops;
  for (const FaceLoop& fl : g.face_loops(face)) {
    std::vector<Entry> seq;
    for (const CurveUse& u : fl) {
      std::vector<Entry> part = use_entries(g, cm, face, u);
      if (part.empty()) continue;
      for (Entry& e : part) e.uv = fs.to_mesher(e.uv);
      if (!seq.empty()) {  // pcurves may be given a period apart
        const Vec2 shift = fs.unwrap(part.front().uv, seq.back().uv) - part.front().uv;
        for (Entry& e : part) e.uv += shift;
      }
      seq.insert(seq.end(), part.begin(), part.end());
    }
    if (seq.size() < 2) continue;
    // Scale of the loop in uv for merge tolerances.
    Vec2 lo = seq[0].uv, hi = seq[0].uv;
    for (const Entry& e : seq) {
      lo = lo.cwiseMin(e.uv);
      hi = hi.cwiseMax(e.uv);
    }
    const double scale = std::max((hi - lo).norm(), 1e-300);
    // Consecutive entries of one node are merged, unless they are a pole's two ends.
    std::vector<Entry> loop;
    auto same_place = [&](const Entry& a, const Entry& b) {
      const double d = (a.uv - b.uv).norm();
      return d <= 1e-9 * scale || (!a.pole && !b.pole && d <= 1e-2 * scale);
    };
    for (const Entry& e : seq) {
      if (!loop.empty() && loop.back().global == e.global) {
        if (same_place(loop.back(), e)) {
          loop.back().pole = loop.back().pole || e.pole;
          continue;
        }
        loop.back().pole = true;
        loop.push_back(e);
        loop.back().pole = true;
        continue;
      }
      loop.push_back(e);
    }
    while (loop.size() > 1 && loop.back().global == loop.front().global) {
      if (same_place(loop.back(), loop.front())) {
        loop.front().pole = loop.front().pole || loop.back().pole;
        loop.pop_back();
      } else {
        loop.back().pole = loop.front().pole = true;
        break;
      }
    }
    if (loop.size() >= 3) loops.push_back(std::move(loop));
  }
  if (loops.empty()) throw Error("face has no boundary loop with 3 or more nodes");

  // Outer loop (largest area) first and counter-clockwise, holes clockwise.
  size_t outer = 0;
  for (size_t i = 1; i < loops.size(); ++i)
    if (std::abs(signed_area(loops[i])) > std::abs(signed_area(loops[outer]))) outer = i;
  std::swap(loops[0], loops[outer]);
  for (size_t i = 0; i < loops.size(); ++i) {
    const double a = signed_area(loops[i]);
    if ((i == 0 && a < 0) || (i > 0 && a > 0)) std::reverse(loops[i].begin(), loops[i].end());
  }

  // Loops that touch at a vertex (a hole meeting the outer loop) share that
  // node: one node per global id and uv position.
  Vec2 lo = loops[0][0].uv, hi = lo;
  for (const auto& loop : loops)
    for (const Entry& e : loop) {
      lo = lo.cwiseMin(e.uv);
      hi = hi.cwiseMax(e.uv);
    }
  const double same_uv = 1e-7 * std::max((hi - lo).norm(), 1e-300);
  std::unordered_map<int, std::vector<int>> nodes_of;  // global id -> local nodes
  FaceMesh fm;
  fm.face = face;
  for (const std::vector<Entry>& loop : loops) {
    std::vector<int> ids;
    const int n = static_cast<int>(loop.size());
    for (int i = 0; i < n; ++i) {
      const Entry& a = loop[i];
      // The face is meshed against its own surface: S(uv), not the curve's
      // xyz, which may lie off the surface by the CAD's edge tolerance. The
      // mesh takes the shared curve node's xyz at assembly.
      SurfaceSample sa = fs.eval(a.uv);
      if (a.pole) sa.n = Vec3::Zero();  // undefined on a pole
      int id = -1;
      for (int k : nodes_of[a.global])
        if ((fm.uv[k] - a.uv).norm() <= same_uv) id = k;
      if (id < 0) {
        id = fm.add_node(a.uv, sa, a.global, a.pole);
        fm.shared_xyz[id] = cm.xyz[a.global];
        nodes_of[a.global].push_back(id);
      }
      ids.push_back(id);
      const Entry& b = loop[(i + 1) % n];
      if (!(a.pole && b.pole && a.global == b.global)) continue;
      // Pole segment: split it like the ring of the mesh next to it (one
      // wanted size away), estimated from the previous node's offset.
      const Entry& x = loop[(i + n - 1) % n];
      int k = 1;
      try {
        const Vec2 offset = x.uv - a.uv;
        const SurfaceSample sx = fs.eval(x.uv);
        double ring = 0;
        Vec3 prev = fs.eval_shape(a.uv + offset).p;
        const int J = 16;
        for (int j = 1; j <= J; ++j) {
          const Vec3 q = fs.eval_shape(a.uv + (b.uv - a.uv) * (double(j) / J) + offset).p;
          ring += (q - prev).norm();
          prev = q;
        }
        // The ring grows about linearly with the distance from the pole, so the
        // ring one h away has about ring/dist edges of length h.
        const double dist = (sx.p - sa.p).norm();
        const double edges = dist > 0 ? ring / dist : ring / std::max(sx.h, 1e-300);
        if (std::isfinite(edges)) k = std::clamp(static_cast<int>(std::lround(edges)), 1, 128);
      } catch (const EvaluationError&) {
        k = 1;  // the surface cannot be evaluated off the pole: one segment
      }
      for (int j = 1; j < k; ++j) {
        const Vec2 uv = a.uv + (b.uv - a.uv) * (double(j) / k);
        SurfaceSample sj = fs.eval(uv);
        sj.n = Vec3::Zero();
        ids.push_back(fm.add_node(uv, sj, a.global, true));
      }
    }
    fm.loops.push_back(std::move(ids));
  }
  return fm;
}

int steady_boundary_normals(FaceMesh& fm, const FaceSurface& fs) {
  constexpr double kCurl = 0.7;      // cos 45 deg: the boundary's normal against the settled one
  constexpr double kSettled = 0.94;  // cos 20 deg: the two inner normals against each other
  constexpr double kDepth[2] = {0.75, 1.05};  // sample depths, in h
  int changed = 0;
  for (const std::vector<int>& loop : fm.loops) {
    const int n = static_cast<int>(loop.size());
    for (int i = 0; i < n; ++i) {
      const int k = loop[i];
      SurfaceSample& sk = fm.s[k];
      if (fm.pole[k] || !(sk.n.squaredNorm() > 0) || !(sk.h > 0)) continue;
      const Vec2 t = fm.uv[loop[(i + 1) % n]] - fm.uv[loop[(i + n - 1) % n]];
      Vec2 d(-t.y(), t.x());  // the domain lies on the loop's left
      if (!(d.norm() > 0)) continue;
      d /= d.norm();
      const double speed = (sk.du * d.x() + sk.dv * d.y()).norm();
      if (!(speed > 0)) continue;
      // Normals at the two depths in space: the uv step from the boundary's
      // speed, halved while it lands too far.
      Vec3 inner[2];
      bool found = true;
      for (int s = 0; s < 2 && found; ++s) {
        const double want = kDepth[s] * sk.h;
        double step = want / speed;
        found = false;
        for (int tries = 0; tries < 8 && std::isfinite(step) && !found; ++tries, step *= 0.5) {
          try {
            const SurfaceSample in = fs.eval_shape(fm.uv[k] + step * d);
            if ((in.p - sk.p).norm() > 1.5 * want || !(in.n.squaredNorm() > 0)) continue;
            inner[s] = in.n;
            found = true;
          } catch (const EvaluationError&) {
          }
        }
      }
      if (found && inner[0].dot(inner[1]) > kSettled && inner[0].dot(sk.n) < kCurl) {
        sk.n = inner[0];
        ++changed;
      }
    }
  }
  return changed;
}

FaceMesh off_bands(const FaceMesh& fm, FaceSurface& fs) {
  if (!fs.has_band()) return fm;
  FaceMesh out = fm;
  for (int i = 0; i < out.num_nodes(); ++i) {
    if (out.pole[i]) continue;
    const Vec2 uv = fs.off_band(out.uv[i]);
    if (uv == out.uv[i]) continue;
    out.uv[i] = uv;
    const Vec3 shared = out.shared_xyz[i];
    out.s[i] = fs.eval(uv);
    out.shared_xyz[i] = shared;
  }
  return out;
}

}  // namespace sizemesh
