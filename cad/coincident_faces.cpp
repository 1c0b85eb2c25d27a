// Faces lying on each other, by area, centre, box and plane (cad/coincident_faces.h).
#include "cad/coincident_faces.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <GeomLib_IsPlanarSurface.hxx>
#include <Standard_Failure.hxx>
#include <gp_Pln.hxx>

#include <algorithm>
#include <cmath>

namespace sizemesh::detail {
namespace {

struct FaceProps {
  double area = 0;
  gp_Pnt centre;
  Bnd_Box box;
  bool planar = false;
  gp_Dir normal;  // outward, by the face's orientation
  double offset = 0;
};

// Beyond `tol`, the areas may differ by the share `rel_area`, the centres by
// the share `rel_centre` of the square root of the area.
bool same_spot(double area_a, const gp_Pnt& centre_a, const Bnd_Box& box_a, double area_b, const gp_Pnt& centre_b,
               const Bnd_Box& box_b, double tol, double rel_area = 1e-6, double rel_centre = 0) {
  const double a = std::max(area_a, area_b);
  if (!(a > 0) || std::abs(area_a - area_b) > rel_area * a + tol * std::sqrt(a)) return false;
  if (centre_a.Distance(centre_b) > tol + rel_centre * std::sqrt(a)) return false;
  double pa[6], pb[6];
  box_a.Get(pa[0], pa[1], pa[2], pa[3], pa[4], pa[5]);
  box_b.Get(pb[0], pb[1], pb[2], pb[3], pb[4], pb[5]);
  for (int k = 0; k < 6; ++k)
    if (std::abs(pa[k] - pb[k]) > 2 * tol) return false;
  return true;
}

// Area, centre, box and plane of f. A B-spline flat within `tol` (an
// OpenVSP cap) counts as planar.
FaceProps face_props(const TopoDS_Face& f, double tol) {
  FaceProps p;
  GProp_GProps g;
  BRepGProp::SurfaceProperties(f, g);
  p.area = std::abs(g.Mass());
  p.centre = g.CentreOfMass();
  BRepBndLib::Add(f, p.box, false);
  if (p.box.IsVoid()) p.area = 0;
  BRepAdaptor_Surface s(f, false);
  gp_Pln pln;
  if (s.GetType() == GeomAbs_Plane) {
    pln = s.Plane();
    p.planar = true;
  } else if (s.GetType() == GeomAbs_BSplineSurface || s.GetType() == GeomAbs_BezierSurface) {
    // A surface collapsed onto a line or a point has no plane (OCCT throws).
    try {
      const Handle(Geom_Surface) surface = BRep_Tool::Surface(f);
      if (!surface.IsNull()) {
        GeomLib_IsPlanarSurface flat(surface, tol);
        if (flat.IsPlanar()) pln = flat.Plan(), p.planar = true;
      }
    } catch (const Standard_Failure&) {
      p.planar = false;
    }
  }
  if (p.planar) {
    p.normal = f.Orientation() == TopAbs_REVERSED ? pln.Axis().Direction().Reversed() : pln.Axis().Direction();
    p.offset = gp_Vec(pln.Location().XYZ()).Dot(gp_Vec(p.normal));
  }
  return p;
}

// True when planar faces with props a and b lie on one plane (either way round).
bool same_plane(const FaceProps& a, const FaceProps& b, double tol) {
  const double dot = a.normal.Dot(b.normal);
  return std::abs(dot) >= 1 - 1e-9 && std::abs(a.offset - (dot > 0 ? 1 : -1) * b.offset) <= tol;
}

}  // namespace

Coincident coincident_pairs(const FaceList& faces, double tol) {
  std::vector<FaceProps> p(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) p[i] = face_props(faces[i], tol);
  Coincident out;
  std::vector<bool> used(faces.size(), false);
  for (size_t i = 0; i < faces.size(); ++i)
    for (size_t j = i + 1; j < faces.size() && !used[i]; ++j) {
      if (used[j] || !same_spot(p[i].area, p[i].centre, p[i].box, p[j].area, p[j].centre, p[j].box, tol)) continue;
      out.push_back({{static_cast<int>(i)}, {static_cast<int>(j)}});
      used[i] = used[j] = true;
    }
  // Groups: the planar faces left, in clusters on one plane whose boxes
  // touch; a cluster split in two parts that cover the same region twice
  // (the sewing may have turned both parts the same way, so their
  // orientation does not tell them apart). Small clusters only: every split
  // is tried.
  constexpr size_t kMaxCluster = 12;
  std::vector<FaceGroup> clusters;
  for (size_t i = 0; i < faces.size(); ++i) {
    if (used[i] || !p[i].planar || !(p[i].area > 0)) continue;
    FaceGroup* into = nullptr;
    for (auto& c : clusters) {
      if (!same_plane(p[c.front()], p[i], tol)) continue;
      const bool touches = std::any_of(c.begin(), c.end(), [&](int j) {
        Bnd_Box grown = p[j].box;
        grown.Enlarge(tol);
        return !grown.IsOut(p[i].box);
      });
      if (touches) {
        into = &c;
        break;
      }
    }
    if (into) into->push_back(static_cast<int>(i));
    else clusters.push_back({static_cast<int>(i)});
  }
  for (const FaceGroup& c : clusters) {
    if (c.size() < 3 || c.size() > kMaxCluster) continue;
    // Part one holds the cluster's first face; the rest of the faces by bit.
    for (unsigned mask = 0; mask < (1u << (c.size() - 1)); ++mask) {
      FaceGroup one{c.front()}, other;
      for (size_t k = 1; k < c.size(); ++k) ((mask >> (k - 1)) & 1 ? one : other).push_back(c[k]);
      if (other.empty()) continue;
      auto sum = [&](const FaceGroup& g, double& area, gp_Pnt& centre, Bnd_Box& box) {
        gp_XYZ moment;
        area = 0;
        for (int j : g) area += p[j].area, moment += p[j].area * p[j].centre.XYZ(), box.Add(p[j].box);
        centre = gp_Pnt(moment / area);
      };
      double area_one, area_other;
      gp_Pnt centre_one, centre_other;
      Bnd_Box box_one, box_other;
      sum(one, area_one, centre_one, box_one);
      sum(other, area_other, centre_other, box_other);
      // Each part a cap cut along its own line and approximated apart: their
      // areas agree to a part in a hundred, their centres to a hundredth of
      // their size, their boxes within `tol` (the repair sews the result
      // before it keeps it).
      if (same_spot(area_one, centre_one, box_one, area_other, centre_other, box_other, tol, 1e-2, 1e-2)) {
        out.push_back({one, other});
        break;
      }
    }
  }
  return out;
}

std::vector<std::pair<int, int>> face_to_face(const std::vector<TopoDS_Shape>& parts, double tol) {
  std::vector<FaceList> faces(parts.size());
  std::vector<std::vector<FaceProps>> props(parts.size());
  std::vector<Bnd_Box> box(parts.size());
  std::vector<std::vector<Bnd_Box>> face_box(parts.size());
  for (size_t k = 0; k < parts.size(); ++k) {
    faces[k] = faces_of(parts[k]);
    BRepBndLib::Add(parts[k], box[k], false);
    box[k].Enlarge(tol);
    for (const auto& f : faces[k]) BRepBndLib::Add(f, face_box[k].emplace_back(), false);
  }
  // Props of a face only once some other component's box holds its box.
  const auto held = [&](size_t k, size_t i, size_t other) {
    const Bnd_Box& b = face_box[k][i];
    double q[6];
    if (b.IsVoid()) return false;
    b.Get(q[0], q[1], q[2], q[3], q[4], q[5]);
    return !box[other].IsOut(gp_Pnt(q[0], q[1], q[2])) && !box[other].IsOut(gp_Pnt(q[3], q[4], q[5]));
  };
  std::vector<std::vector<char>> known(parts.size());
  for (size_t k = 0; k < parts.size(); ++k) known[k].assign(faces[k].size(), 0), props[k].resize(faces[k].size());
  const auto prop = [&](size_t k, size_t i) -> const FaceProps& {
    if (!known[k][i]) {
      try {
        props[k][i] = face_props(faces[k][i], tol);
      } catch (const Standard_Failure&) {
        props[k][i] = FaceProps{};  // no area: matches nothing
      }
      known[k][i] = 1;
    }
    return props[k][i];
  };
  std::vector<std::pair<int, int>> out;
  std::vector<char> paired(parts.size(), 0);
  for (size_t a = 0; a < parts.size(); ++a)
    for (size_t b = a + 1; b < parts.size() && !paired[a]; ++b) {
      if (paired[b] || box[a].IsOut(box[b])) continue;
      std::vector<size_t> on_a, on_b;  // faces of each within the other's box
      for (size_t i = 0; i < faces[a].size(); ++i)
        if (held(a, i, b)) on_a.push_back(i);
      for (size_t j = 0; j < faces[b].size(); ++j)
        if (held(b, j, a)) on_b.push_back(j);
      bool meet = false;
      for (size_t i : on_a)
        for (size_t j : on_b) {
          const FaceProps &x = prop(a, i), &y = prop(b, j);
          meet = meet || same_spot(x.area, x.centre, x.box, y.area, y.centre, y.box, tol);
        }
      // On each plane of a's faces, the faces of a and of b there.
      for (size_t i = 0; i < on_a.size() && !meet; ++i) {
        const FaceProps& x = prop(a, on_a[i]);
        if (!x.planar || !(x.area > 0)) continue;
        double area[2] = {0, 0};
        gp_XYZ moment[2];
        Bnd_Box group[2];
        for (int side = 0; side < 2; ++side)
          for (size_t j : side == 0 ? on_a : on_b) {
            const FaceProps& y = prop(side == 0 ? a : b, j);
            if (!y.planar || !same_plane(x, y, tol)) continue;
            area[side] += y.area, moment[side] += y.area * y.centre.XYZ(), group[side].Add(y.box);
          }
        if (area[0] > 0 && area[1] > 0)
          meet = same_spot(area[0], gp_Pnt(moment[0] / area[0]), group[0], area[1], gp_Pnt(moment[1] / area[1]),
                           group[1], tol, 1e-2, 1e-2);
      }
      if (!meet) continue;
      paired[a] = paired[b] = 1;
      out.emplace_back(static_cast<int>(a), static_cast<int>(b));
    }
  return out;
}

}  // namespace sizemesh::detail
