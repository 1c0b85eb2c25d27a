// Geometry preparation: components of the sewn shape, their repair, and the
// union of the closed ones into one wetted surface.
//
// Repair works per open component and judges every change by re-sewing it:
//  - coincident face pairs (two halves of a body that both carry the cap
//    between them) are taken out when that leaves no more free curves;
//  - faces with a free curve are taken out one at a time, best first, while
//    each removal lowers the free-curve count; the result is kept only when
//    the component closes, and each face taken out must lie inside the closed
//    volume (an internal sheet such as a wing's planform plane), otherwise it
//    stays as a sheet of its own. A component that does not close is kept as
//    it was read: nothing is lost.
// The union of the closed components is geometry/unite.cpp; open components
// left are imprinted on the bodies by the general fuse. Every attempt runs
// within the union's time budget, and every result face records its source
// face.
#include "geometry/prepare.h"
#include "geometry/stopwatch.h"

#include <BOPAlgo_Alerts.hxx>
#include <BOPAlgo_Builder.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepAlgoAPI_Section.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <GeomLib_IsPlanarSurface.hxx>
#include <gp_Pln.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <ShapeFix_Solid.hxx>
#include <ShapeBuild_ReShape.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_MapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <thread>

#include <tbb/task_arena.h>

#include "geometry/deadline.h"
#include "geometry/off_thread.h"
#include "geometry/occt_model.h"

namespace sizemesh {
namespace {

using FaceList = std::vector<TopoDS_Face>;

// Bounds on the repair's trials: sewing one component per trial.
constexpr int kMaxCandidates = 16;
constexpr int kMaxRounds = 8;
// Folds are split where the surface turns over within this share of the
// model's diagonal: half the default smallest element (sizing/params.h).
constexpr double kFoldBand = 5e-4;

FaceList faces_of(const TopoDS_Shape& s) {
  FaceList out;
  TopTools_IndexedMapOfShape fm;
  TopExp::MapShapes(s, TopAbs_FACE, fm);
  for (int i = 1; i <= fm.Extent(); ++i) out.push_back(TopoDS::Face(fm(i)));
  return out;
}

TopoDS_Compound compound_of(const FaceList& faces) {
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  for (const auto& f : faces) b.Add(c, f);
  return c;
}

struct Sewn {
  TopoDS_Shape shape;
  int free_curves = 0;
  std::shared_ptr<BRepBuilderAPI_Sewing> sewing;
  TopoDS_Face after(const TopoDS_Face& f) const {
    return sewing->IsModified(f) ? TopoDS::Face(sewing->Modified(f)) : f;
  }
};

// Says "stop" once `flag` is set: a sewing no one waits for any more.
class FlagIndicator : public Message_ProgressIndicator {
 public:
  explicit FlagIndicator(const std::atomic<bool>& flag) : flag_(flag) {}
  Standard_Boolean UserBreak() override { return flag_.load(); }
  void Show(const Message_ProgressScope&, const Standard_Boolean) override {}

 private:
  const std::atomic<bool>& flag_;
};

// The faces sewn at `tol`; abandoned (its result of no use) once `stop` is set.
Sewn sew(const FaceList& faces, double tol, const std::atomic<bool>* stop = nullptr) {
  Sewn s;
  s.sewing = std::make_shared<BRepBuilderAPI_Sewing>(tol);
  for (const auto& f : faces) s.sewing->Add(f);
  if (stop) {
    Handle(FlagIndicator) indicator = new FlagIndicator(*stop);
    s.sewing->Perform(indicator->Start());
  } else {
    s.sewing->Perform();
  }
  s.shape = s.sewing->SewedShape();
  if (s.shape.IsNull()) s.shape = compound_of(faces);
  else mend_sewn_edges(s.shape, tol);
  s.free_curves = count_free_curves(s.shape);
  return s;
}

// `area`: exact face areas known from loading (others are computed).
Component describe(const TopoDS_Shape& s, const TopTools_DataMapOfShapeReal& area) {
  Component c;
  const FaceList faces = faces_of(s);
  c.faces = static_cast<int>(faces.size());
  c.free_curves = count_free_curves(s);
  c.closed = c.free_curves == 0 && (s.ShapeType() == TopAbs_SOLID || s.ShapeType() == TopAbs_SHELL);
  for (const auto& f : faces) {
    if (area.IsBound(f)) {
      c.area += area(f);
      continue;
    }
    GProp_GProps g;
    BRepGProp::SurfaceProperties(f, g);
    c.area += std::abs(g.Mass());
  }
  Bnd_Box box;
  BRepBndLib::Add(s, box, false);
  if (!box.IsVoid()) {
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    c.bbox_min = {x0, y0, z0};
    c.bbox_max = {x1, y1, z1};
  }
  return c;
}

// The connected pieces of the sewn shape: solids, shells outside solids, and
// faces outside shells.
std::vector<TopoDS_Shape> components_of(const TopoDS_Shape& shape) {
  std::vector<TopoDS_Shape> out;
  for (TopExp_Explorer ex(shape, TopAbs_SOLID); ex.More(); ex.Next()) out.push_back(ex.Current());
  for (TopExp_Explorer ex(shape, TopAbs_SHELL, TopAbs_SOLID); ex.More(); ex.Next()) out.push_back(ex.Current());
  for (TopExp_Explorer ex(shape, TopAbs_FACE, TopAbs_SHELL); ex.More(); ex.Next()) out.push_back(ex.Current());
  return out;
}

// Faces of `faces` whose sewn image has a free curve.
FaceList faces_on_free_curves(const FaceList& faces, const Sewn& s) {
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(s.shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  FaceList out;
  for (const auto& f : faces) {
    const TopoDS_Face g = s.after(f);
    for (TopExp_Explorer ex(g, TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
      const int k = edge_faces.FindIndex(e);
      if (k == 0 || BRep_Tool::Degenerated(e) || BRep_Tool::IsClosed(e, g)) continue;
      if (edge_faces(k).Extent() == 1) {
        out.push_back(f);
        break;
      }
    }
  }
  return out;
}

double face_area(const TopoDS_Face& f) {
  GProp_GProps g;
  BRepGProp::SurfaceProperties(f, g);
  return std::abs(g.Mass());
}

double volume_of(const TopoDS_Shape& solid) {
  GProp_GProps g;
  BRepGProp::VolumeProperties(solid, g);
  return std::abs(g.Mass());
}

// An open component whose faces all lie on one plane (`plane` gets it) and
// whose outer rim is a circle: the free curves' points beyond half the
// largest distance from the centroid all lie within 5% of it (an annulus's
// inner rim is not the rim). A propeller's or rotor's disk.
bool flat_disk(const TopoDS_Shape& s, double tol, gp_Pln& plane) {
  bool any = false;
  for (const auto& f : faces_of(s)) {
    const Handle(Geom_Surface) g = BRep_Tool::Surface(f);
    if (g.IsNull()) return false;
    GeomLib_IsPlanarSurface planar(g, tol);
    if (!planar.IsPlanar()) return false;
    const gp_Pln p = planar.Plan();
    if (!any) plane = p, any = true;
    else if (!plane.Axis().IsParallel(p.Axis(), 1e-6) || plane.Distance(p.Location()) > tol) return false;
  }
  if (!any) return false;
  GProp_GProps props;
  BRepGProp::SurfaceProperties(s, props);
  const gp_Pnt centre = props.CentreOfMass();
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(s, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  std::vector<double> r;
  for (int i = 1; i <= edge_faces.Extent(); ++i) {
    const TopoDS_Edge e = TopoDS::Edge(edge_faces.FindKey(i));
    if (edge_faces(i).Extent() != 1 || BRep_Tool::Degenerated(e)) continue;
    const BRepAdaptor_Curve c(e);
    for (int k = 0; k <= 8; ++k)
      r.push_back(centre.Distance(c.Value(c.FirstParameter() + (c.LastParameter() - c.FirstParameter()) * k / 8)));
  }
  if (r.empty()) return false;
  const double most = *std::max_element(r.begin(), r.end());
  return std::all_of(r.begin(), r.end(), [&](double d) { return d < 0.5 * most || d > 0.95 * most; });
}

// A flat disk on `plane` that one of the `solids` passes through: the
// solid's section by the plane lies within the disk (a propeller's
// actuator disk around its nacelle or spinner). It has fluid on both sides
// and bounds no volume, so it is no wall of the wetted surface; imprinted
// on the body it would leave boundary and non-manifold edges. A flat sheet
// a body only touches or ends in (a plate fin on a fuselage) is a wall.
bool pierced(const TopoDS_Shape& sheet, const gp_Pln& plane, const std::vector<TopoDS_Shape>& solids, double tol) {
  Bnd_Box sheet_box;
  BRepBndLib::Add(sheet, sheet_box);
  const FaceList faces = faces_of(sheet);
  for (const auto& solid : solids) {
    Bnd_Box box;
    BRepBndLib::Add(solid, box);
    if (box.IsOut(sheet_box)) continue;
    try {
      BRepAlgoAPI_Section section(solid, plane, false);
      section.Build();
      if (!section.IsDone()) continue;
      int points = 0;
      bool inside = true;
      for (TopExp_Explorer ex(section.Shape(), TopAbs_EDGE); ex.More() && inside; ex.Next()) {
        const BRepAdaptor_Curve c(TopoDS::Edge(ex.Current()));
        for (int i = 0; i <= 8 && inside; ++i, ++points) {
          const gp_Pnt p = c.Value(c.FirstParameter() + (c.LastParameter() - c.FirstParameter()) * i / 8);
          inside = std::any_of(faces.begin(), faces.end(), [&](const TopoDS_Face& f) {
            const TopAbs_State state = BRepClass_FaceClassifier(f, p, tol).State();
            return state == TopAbs_IN || state == TopAbs_ON;
          });
        }
      }
      if (inside && points > 0) return true;
    } catch (const Standard_Failure&) {
      continue;
    }
  }
  return false;
}

// Faces lying on each other: pairs of single faces (same area, centre and
// box within `tol`), then, on one plane, two groups of faces that cover the
// same region (two halves' root caps, each cut in two along its own line).
using FaceGroup = std::vector<int>;
using Coincident = std::vector<std::pair<FaceGroup, FaceGroup>>;

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

// What one round of the repair may take out: each face on a free curve alone,
// and each connected group of them (faces sharing a curve in the sewing):
// a planform plane in pieces (one per wing segment and side) opens as much
// as it closes when one piece goes, and closes only when all go together.
std::vector<FaceList> removal_options(const FaceList& cand, const Sewn& s) {
  std::vector<FaceList> out;
  for (const auto& f : cand) out.push_back({f});
  std::vector<int> group(cand.size());
  for (size_t i = 0; i < cand.size(); ++i) group[i] = static_cast<int>(i);
  const std::function<int(int)> root = [&](int i) { return group[i] == i ? i : group[i] = root(group[i]); };
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(s.shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  for (size_t i = 0; i < cand.size(); ++i)
    for (size_t j = i + 1; j < cand.size(); ++j) {
      const TopoDS_Face a = s.after(cand[i]), b = s.after(cand[j]);
      bool touch = false;
      for (TopExp_Explorer ex(a, TopAbs_EDGE); ex.More() && !touch; ex.Next())
        for (TopExp_Explorer ey(b, TopAbs_EDGE); ey.More() && !touch; ey.Next()) touch = ex.Current().IsSame(ey.Current());
      if (touch) group[root(static_cast<int>(i))] = root(static_cast<int>(j));
    }
  std::map<int, FaceList> groups;
  for (size_t i = 0; i < cand.size(); ++i) groups[root(static_cast<int>(i))].push_back(cand[i]);
  for (const auto& [r, faces] : groups)
    if (faces.size() > 1) out.push_back(faces);
  return out;
}

// Points inside the face (not on its boundary), found on a uv grid: the
// centre first, then outwards; at most `wanted`, spread over the grid.
std::vector<gp_Pnt> interior_points(const TopoDS_Face& f, int wanted) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  BRepTopAdaptor_FClass2d inside(f, Precision::PConfusion());
  BRepAdaptor_Surface s(f, false);
  constexpr int n = 9;
  std::vector<gp_Pnt> found;
  for (int k = 0; k < n * n; ++k) {
    const int i = (n / 2 + (k % n + 1) / 2 * ((k % n) % 2 ? 1 : -1)) % n;
    const int j = (n / 2 + (k / n + 1) / 2 * ((k / n) % 2 ? 1 : -1)) % n;
    const double u = u0 + (u1 - u0) * (i + 0.5) / n, v = v0 + (v1 - v0) * (j + 0.5) / n;
    if (inside.Perform(gp_Pnt2d(u, v)) == TopAbs_IN) found.push_back(s.Value(u, v));
  }
  if (static_cast<int>(found.size()) <= wanted) return found;
  std::vector<gp_Pnt> out;
  for (int k = 0; k < wanted; ++k) out.push_back(found[k * found.size() / wanted]);
  return out;
}

// Solids asked whether a face lies inside one of them or on its boundary:
// most of a few points spread over it do, for one solid. One point alone may
// sit where another body touches the face (a jury strut's foot on a strut), or
// be misjudged by the classifier that close to the boundary (a planform plane
// in a thin wing). Solids whose box holds no more than half the points are
// not asked: the classifier can take seconds a point on a solid with crossing
// faces.
class Solids {
 public:
  Solids(const std::vector<TopoDS_Shape>& solids, double tol)
      : solids_(solids), classifiers_(solids.size()), tol_(tol) {
    for (const auto& s : solids_) {
      boxes_.emplace_back();
      BRepBndLib::Add(s, boxes_.back(), false);
      boxes_.back().Enlarge(tol);
    }
  }
  // Every one of `n` points spread over f inside one solid or on its
  // boundary: a face wholly inside, not one that reaches out of it.
  bool hold_whole(const TopoDS_Face& f, int n) const {
    const std::vector<gp_Pnt> points = interior_points(f, n);
    if (points.empty()) return false;
    for (size_t i = 0; i < solids_.size(); ++i) {
      if (std::any_of(points.begin(), points.end(), [&](const gp_Pnt& p) { return boxes_[i].IsOut(p); })) continue;
      if (std::all_of(points.begin(), points.end(), [&](const gp_Pnt& p) { return within(i, p); })) return true;
    }
    return false;
  }
  // Most of 5 points spread over f inside one solid or on its boundary.
  bool hold(const TopoDS_Face& f) const {
    const std::vector<gp_Pnt> points = interior_points(f, 5);
    for (size_t i = 0; i < solids_.size(); ++i) {
      const auto in_box =
          std::count_if(points.begin(), points.end(), [&](const gp_Pnt& p) { return !boxes_[i].IsOut(p); });
      if (2 * in_box <= static_cast<long>(points.size())) continue;
      const auto in = std::count_if(points.begin(), points.end(), [&](const gp_Pnt& p) { return within(i, p); });
      if (2 * in > static_cast<long>(points.size())) return true;
    }
    return false;
  }

 private:
  // p inside solid i or on its boundary. The classifier is loaded once per
  // solid (loading maps its faces and boxes, most of a classification's cost).
  bool within(size_t i, const gp_Pnt& p) const {
    if (!classifiers_[i]) classifiers_[i] = std::make_unique<BRepClass3d_SolidClassifier>(solids_[i]);
    classifiers_[i]->Perform(p, tol_);
    const TopAbs_State st = classifiers_[i]->State();
    return st == TopAbs_IN || st == TopAbs_ON;
  }
  std::vector<TopoDS_Shape> solids_;
  mutable std::vector<std::unique_ptr<BRepClass3d_SolidClassifier>> classifiers_;
  std::vector<Bnd_Box> boxes_;
  double tol_;
};

// The solids bounded by the shells of a sewn shape (a wing whose halves
// close each on its own sews into two shells), or none when one of them
// bounds no solid.
std::vector<TopoDS_Shape> solids_of(const TopoDS_Shape& sewn) {
  std::vector<TopoDS_Shape> out;
  for (TopExp_Explorer ex(sewn, TopAbs_SHELL); ex.More(); ex.Next()) {
    const TopoDS_Solid solid = solid_from_shell(TopoDS::Shell(ex.Current()));
    if (solid.IsNull()) return {};
    out.push_back(solid);
  }
  return out;
}

double volume_of(const std::vector<TopoDS_Shape>& solids) {
  double v = 0;
  for (const auto& s : solids) v += volume_of(s);
  return v;
}

// The repair of one open component. A null `closed` on return means "keep
// the component as it was".
struct Repair {
  TopoDS_Shape closed;    // the closed, sewn component (a shell), or null
  TopoDS_Shape half_open;  // or a half model's shell, open only on its plane
  Sewn sewn;              // the sewing that made it
  FaceList kept;          // faces of `closed`, before that sewing
  FaceList sheets;        // faces taken out that lie outside the component's volume
  std::vector<std::pair<TopoDS_Face, TopoDS_Face>> split;  // (face read, piece) of faces split at a slit
  int duplicates = 0, internal = 0, caps = 0;
  int half_model_axis = -1;  // the half-model plane its free loops lie on
};

// Components that meet face to face: faces of one lie on faces of another
// (a wing's two halves, each closed by its own root cap on the plane
// between them, one of them perhaps left open by the export): a single face
// on a single face (same area, centre and box within `tol`), or on one
// plane the faces of each, cut along different lines, covering the same
// region (areas within a part in a hundred, centres within a hundredth of
// their size). Neither is a wall: the two go through the repair as one
// body, which takes such faces out and sews the halves together. Returns
// pairs (a, b), a < b, each component in one pair at most.
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

// Closed edges shorter than the sewing tolerance dropped from their wires:
// what sewing leaves where the ends of two curves met a few tolerances
// apart (a loop of microns at the leading edge where two halves of a tail
// were sewn). Both its ends are one vertex, so the wires stay closed
// without it; kept, the mesher would put a closed curve's three segments on
// one spot and the faces on either side would fold there. `count` gets the
// edges dropped.
TopoDS_Shape drop_small_loops(const TopoDS_Shape& shape, double tol, const Follow& follow, int& count) {
  count = 0;
  Handle(ShapeBuild_ReShape) reshape = new ShapeBuild_ReShape;
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(shape, TopAbs_EDGE, edges);
  try {
    for (int i = 1; i <= edges.Extent(); ++i) {
      const TopoDS_Edge& e = TopoDS::Edge(edges(i));
      TopoDS_Vertex v0, v1;
      TopExp::Vertices(e, v0, v1);
      if (BRep_Tool::Degenerated(e) || v0.IsNull() || !v0.IsSame(v1)) continue;
      const BRepAdaptor_Curve c(e);
      if (!c.Is3DCurve() || !(GCPnts_AbscissaPoint::Length(c) < tol)) continue;
      reshape->Remove(e);
      ++count;
    }
    if (count == 0) return shape;
    const TopoDS_Shape result = reshape->Apply(shape);
    if (result.IsNull() || !BRepCheck_Analyzer(result).IsValid()) return count = 0, shape;
    for (const auto& f : faces_of(shape)) {
      const TopoDS_Shape now = reshape->Apply(f);
      if (!now.IsNull() && now.ShapeType() == TopAbs_FACE && !now.IsSame(f)) follow(f, TopoDS::Face(now));
    }
    return result;
  } catch (const Standard_Failure&) {
    count = 0;
    return shape;
  }
}

// Faces of `faces` and of `more`.
FaceList joined(FaceList faces, const FaceList& more) {
  faces.insert(faces.end(), more.begin(), more.end());
  return faces;
}

// Coincident faces or groups of `faces` taken out of `current` (sewn as `now` at
// tolerance t): both (the caps between two halves of one body) when that
// does not open the component further, else one of them (a duplicate).
// Returns the faces taken out. Given up once `stop` is set.
int drop_coincident(const FaceList& faces, const Coincident& pairs, double t, FaceList& current, Sewn& now,
                    const std::atomic<bool>* stop = nullptr) {
  int dropped = 0;
  for (const auto& [one, other] : pairs) {
    if (stop && *stop) break;
    FaceGroup both = one;
    both.insert(both.end(), other.begin(), other.end());
    for (const FaceGroup& drop : {both, other}) {
      FaceList trial;
      for (const auto& f : current)
        if (std::none_of(drop.begin(), drop.end(), [&](int d) { return f.IsSame(faces[d]); })) trial.push_back(f);
      Sewn s = sew(trial, t, stop);
      if (s.free_curves <= now.free_curves) {
        dropped += static_cast<int>(drop.size());
        current = trial;
        now = s;
        break;
      }
    }
  }
  return dropped;
}

Repair repair_component(const FaceList& read, double tol, double component_diagonal, const HalfModelPlanes& half,
                        int cap_axis) {
  Repair r;
  const FaceList faces = split_pinched(read, tol, r.split);
  const auto pairs = coincident_pairs(faces, tol);
  // A looser sewing may close it alone (a sewing ladder up to 1e-3 of the
  // component's size), judged by the free curves left once coincident faces
  // (two halves' root caps, back to back) are out: kept, they would lie
  // inside the closed body.
  // The rest starts from the sewing at `tol` (the ladder's first rung).
  // The rungs are sewn in parallel: the first on the faces themselves, on
  // this thread; each other on a copy of them (sewing widens the tolerances
  // of what it sews), given up once the first closes the component. A later
  // rung that closes it is sewn again on the faces themselves, after the
  // first, as it would have been in turn.
  std::vector<double> rungs;
  for (double t : {tol, 10 * tol, 100 * tol})
    if (t == tol || t <= 1e-3 * component_diagonal) rungs.push_back(t);
  struct Rung {
    FaceList trial;
    Sewn sewn;
    int dropped = 0;
    bool closes = false;
  };
  std::atomic<bool> first_closes{false};
  const auto climb = [&](double t, const FaceList& own, const std::atomic<bool>* stop) {
    Rung r{own, sew(own, t, stop)};
    r.dropped = pairs.empty() ? 0 : drop_coincident(own, pairs, t, r.trial, r.sewn, stop);
    r.closes = r.sewn.free_curves == 0 && TopExp_Explorer(r.sewn.shape, TopAbs_SHELL).More();
    return r;
  };
  std::vector<Rung> climbed(rungs.size());
  const auto later_rungs = [&] {
    off_this_thread(rungs.size() - 1, [&](size_t j) {
      BRepBuilderAPI_Copy copy(compound_of(faces));
      FaceList own;
      for (const auto& f : faces) own.push_back(TopoDS::Face(copy.Modified(f).First()));
      climbed[j + 1] = climb(rungs[j + 1], own, &first_closes);
    });
  };
  const auto first_rung = [&] {
    climbed[0] = climb(rungs[0], faces, nullptr);
    if (climbed[0].closes) first_closes = true;
  };
  if (tbb::this_task_arena::max_concurrency() > 1) {
    std::exception_ptr failure;
    std::thread beside([&] {
      try {
        later_rungs();
      } catch (...) {
        failure = std::current_exception();
      }
    });
    try {
      first_rung();
    } catch (...) {
      first_closes = true;
      beside.join();
      throw;
    }
    beside.join();
    if (failure) std::rethrow_exception(failure);
  } else {
    first_rung();
    later_rungs();
  }
  for (size_t i = 0; i < rungs.size(); ++i) {
    if (!climbed[i].closes) continue;
    Rung c = i == 0 ? climbed[0] : climb(rungs[i], faces, nullptr);
    if (!c.closes) continue;
    r.closed = c.sewn.shape;
    r.sewn = c.sewn;
    r.kept = c.trial;
    r.duplicates = c.dropped;
    return r;
  }
  FaceList current = climbed[0].trial;
  Sewn now = climbed[0].sewn;
  r.duplicates = climbed[0].dropped;
  // Faces on free curves, best first, while each removal closes more. What
  // is taken out stays under half the component's area: an internal plane or
  // a cap, never the skin that bounds the body.
  FaceList removed;
  double area_left = 0, area_out = 0;
  for (const auto& f : current) area_left += face_area(f);
  for (int round = 0; round < kMaxRounds && now.free_curves > 0; ++round) {
    FaceList cand = faces_on_free_curves(current, now);
    if (cand.size() > static_cast<size_t>(kMaxCandidates)) cand.resize(kMaxCandidates);
    const std::vector<FaceList> options = removal_options(cand, now);
    // Each option's trial, sewn on a copy of what it keeps, all in parallel:
    // sewing widens the tolerances of the curves and vertices it sews, so
    // trials on the faces themselves would change each other.
    struct Trial {
      FaceList faces;
      int free_curves = -1;  // -1: not tried
      double volume = -1;    // of the closed result, when it closes
    };
    std::vector<Trial> trials(options.size());
    off_this_thread(options.size(), [&](size_t c) {
      double out = 0;
      for (const auto& f : options[c]) out += face_area(f);
      FaceList trial;
      for (const auto& f : current)
        if (std::none_of(options[c].begin(), options[c].end(), [&](const TopoDS_Face& g) { return g.IsSame(f); }))
          trial.push_back(f);
      if (trial.empty() || area_out + out > 0.5 * area_left) return;
      const Sewn s = sew(faces_of(BRepBuilderAPI_Copy(compound_of(trial)).Shape()), tol);
      trials[c].faces = std::move(trial);
      trials[c].free_curves = s.free_curves;
      if (s.free_curves == 0) {
        const std::vector<TopoDS_Shape> solids = solids_of(s.shape);
        if (!solids.empty()) trials[c].volume = volume_of(solids);
      }
    });
    int best = -1;
    for (size_t c = 0; c < options.size(); ++c) {
      const Trial& t = trials[c];
      if (t.free_curves < 0) continue;
      const int to_beat = best < 0 ? now.free_curves : trials[best].free_curves;
      // Removals that close it alike (a wing's upper skin, lower skin and
      // planform plane all meet on the leading and trailing edges: any two
      // close): the one that encloses the most keeps the skins, so what is
      // taken out is the plane inside them.
      if (t.free_curves < to_beat || (best >= 0 && t.free_curves == to_beat && t.volume > trials[best].volume))
        best = static_cast<int>(c);
    }
    // The best sewn again on the faces themselves: the sewing the rest goes on from.
    Sewn best_sewn;
    if (best >= 0) {
      best_sewn = sew(trials[best].faces, tol);
      if (best_sewn.free_curves >= now.free_curves) best = -1;
    }
    if (best < 0) break;
    for (const auto& g : options[best]) {
      removed.push_back(g);
      area_out += face_area(g);
      current.erase(std::find_if(current.begin(), current.end(), [&](const TopoDS_Face& f) { return f.IsSame(g); }));
    }
    now = best_sewn;
  }
  // Flat loops left open (a tip or a root without its cap) get planar caps.
  if (now.free_curves > 0) {
    const Caps caps = planar_caps(now.shape, tol, half, cap_axis);
    r.half_model_axis = caps.half_model_axis;
    if (!caps.faces.empty()) {
      FaceList trial = joined(current, caps.faces);
      Sewn s = sew(trial, tol);
      if (s.free_curves < now.free_curves) {
        current = trial;
        now = s;
        r.caps = static_cast<int>(caps.faces.size());
      }
    }
  }
  // Open on its half-model plane alone: capped there for a moment, to tell
  // the faces taken out inside it from those outside, and kept open.
  std::vector<TopoDS_Shape> solids;
  if (now.free_curves != 0) {
    if (r.half_model_axis < 0) return {};
    const Sewn capped = sew(joined(current, planar_caps(now.shape, tol, half, r.half_model_axis).faces), tol);
    if (capped.free_curves != 0) return {};
    solids = solids_of(capped.shape);
    r.half_open = now.shape;
  } else {
    solids = solids_of(now.shape);
    r.closed = now.shape;
  }
  // A cap lying on a face (a planform plane and the cap over its rim) bounds no volume.
  if (solids.empty() || volume_of(solids) < 1e-6 * std::pow(component_diagonal, 3)) return {};
  const Solids inside(solids, tol);
  for (const auto& f : removed) {
    if (inside.hold(f)) ++r.internal;
    else r.sheets.push_back(f);
  }
  r.sewn = now;
  r.kept = current;
  return r;
}

double diagonal_of(const Component& c) { return (c.bbox_max - c.bbox_min).norm(); }

// The general fuse of the bodies and the sheets (BOPAlgo_Builder): every curve
// where a sheet meets a body or another sheet is shared by the faces on both
// sides, and sheet pieces inside a body (or lying on its surface) are
// dropped. Returns the kept faces as a compound, oriented as in the result,
// or a null shape when the fuse fails.
TopoDS_Shape imprint_sheets(const std::vector<TopoDS_Shape>& bodies, const std::vector<TopoDS_Shape>& sheets,
                            double tol, const Deadline& deadline, const Follow& follow, Preparation& info) {
  // The bodies are one argument: the fuse intersects only shapes of
  // different arguments, so bodies already united (or left apart for the
  // mesh-level union) are not intersected with each other again.
  TopoDS_Compound all_bodies;
  BRep_Builder builder;
  builder.MakeCompound(all_bodies);
  for (const auto& s : bodies) builder.Add(all_bodies, s);
  std::vector<TopoDS_Shape> parts{all_bodies};
  parts.insert(parts.end(), sheets.begin(), sheets.end());
  const double seconds = deadline.remaining();
  const FuseStep step = fuse_in_child(parts, seconds, [&](bool parallel) {
    FuseStep out;
    TopTools_ListOfShape args;
    for (const auto& p : parts) args.Append(p);
    BOPAlgo_Builder fuse;
    fuse.SetArguments(args);
    fuse.SetRunParallel(parallel);
    Handle(DeadlineIndicator) stop = new DeadlineIndicator(seconds);
    try {
      fuse.Perform(stop->Start());
    } catch (const Standard_Failure&) {
      fuse.AddError(new BOPAlgo_AlertBuilderFailed);
    }
    if (fuse.HasErrors() || fuse.Shape().IsNull()) {
      out.failure = stop->UserBreak() ? "the sheets could not be imprinted within the preparation's time"
                                      : "the sheets could not be imprinted";
      return out;
    }
    for (const auto& p : parts)
      for (const auto& f : faces_of(p))
        for (const auto& piece : pieces_of(fuse, f)) out.pieces.emplace_back(f, piece);
    out.shape = fuse.Shape();
    return out;
  });
  if (step.shape.IsNull()) {
    info.fallback = step.failure;
    return {};
  }
  std::vector<TopoDS_Shape> solids;
  for (const auto& s : bodies)
    for (TopExp_Explorer ex(s, TopAbs_SOLID); ex.More(); ex.Next()) solids.push_back(ex.Current());
  TopTools_MapOfShape sheet_faces, dropped;
  for (const auto& s : sheets)
    for (const auto& f : faces_of(s)) sheet_faces.Add(f);
  // Sheet pieces inside a body (or on its surface) go; every other piece keeps its source.
  const Solids inside(solids, tol);
  for (const auto& [f, piece] : step.pieces) {
    if (sheet_faces.Contains(f) && inside.hold(piece)) dropped.Add(piece);
    else follow(f, piece);
  }
  info.sheets_imprinted = static_cast<int>(sheets.size());
  info.sheet_pieces_dropped = dropped.Extent();
  TopoDS_Compound out;
  BRep_Builder b;
  b.MakeCompound(out);
  TopTools_MapOfShape added;
  for (TopExp_Explorer ex(step.shape, TopAbs_FACE); ex.More(); ex.Next())
    if (!dropped.Contains(ex.Current()) && added.Add(ex.Current())) b.Add(out, ex.Current());
  return out;
}

// Without a flow domain, the union of meshes takes over what the B-rep union
// leaves (mesher/mesh_union.h) in seconds, and closed: 1.5 s per component
// within 4 to 8 s, repair included, so the preparation ends within 10 s with
// its last splits. A fuse of OpenVSP's B-splines of hundreds of spans (every
// edge against every face it reaches) that would take 10 s to a minute is
// not waited for: the union of meshes does the same in 2 to 5 s. The fuses
// that end (the F-16's and the manta's, 2 and 2.6 s) end with room to
// spare. Inside a flow domain nothing takes over: 4 s per component, at
// least 12 s.
bool meshes_take_over(const LoadOptions& o) { return !o.domain.active(); }

double default_budget(const LoadOptions& o, size_t components) {
  if (o.union_seconds > 0) return o.union_seconds;
  const double n = static_cast<double>(components);
  return meshes_take_over(o) ? std::clamp(1.5 * n, 4.0, 8.0) : std::max(12.0, 4.0 * n);
}

}  // namespace

double union_budget(const CadFile& cad, const LoadOptions& options) {
  return default_budget(options, components_of(cad.impl().shape).size());
}

FaceList pieces_of(BOPAlgo_Builder& fuse, const TopoDS_Face& f) {  // history queries are not const in OCCT
  FaceList out;
  for (const auto& p : fuse.Modified(f)) out.push_back(TopoDS::Face(p));
  if (out.empty() && !fuse.IsDeleted(f)) out.push_back(f);
  return out;
}

PreparedShape prepare_shape(const TopoDS_Shape& sewn, const TopTools_IndexedMapOfShape& original,
                            const TopTools_DataMapOfShapeReal& area, double tol, double diagonal,
                            const LoadOptions& options, Preparation& info) {
  const bool unite = options.unite && options.sew;
  PreparedShape out;
  info = Preparation{};
  info.union_requested = unite;
  info.faces_before = original.Extent();
  for (int i = 1; i <= original.Extent(); ++i) out.source.Bind(original(i), i);
  const std::vector<TopoDS_Shape> parts = components_of(sewn);
  info.seconds_budget = default_budget(options, parts.size());
  const Deadline deadline(info.seconds_budget);
  for (const auto& s : parts) {
    info.components.push_back(describe(s, area));
    for (const auto& f : faces_of(s)) info.components.back().face_ids.push_back(original.FindIndex(f));
  }
  if (!unite) {
    for (auto& c : info.components) c.role = c.closed ? "solid" : "sheet";
    out.shape = sewn;
    info.faces_after = info.faces_before;
    return out;
  }

  Vec3 lo = info.components.front().bbox_min, hi = info.components.front().bbox_max;
  for (const Component& c : info.components) lo = lo.cwiseMin(c.bbox_min), hi = hi.cwiseMax(c.bbox_max);
  const HalfModelPlanes half = half_model_planes(lo, hi, tol);
  // Repair each open component; collect the solids and sheets.
  std::vector<TopoDS_Shape> solids, sheets;
  std::vector<TopoDS_Shape> invalid;  // solids no mending makes valid: for the union of meshes
  std::vector<int> solid_component, sheet_component;
  FaceList loose;
  std::vector<int> loose_component;
  std::vector<std::pair<int, gp_Pln>> flat;  // components that are flat open disks, their plane
  const Follow follow = [&](const TopoDS_Face& from, const TopoDS_Face& to) {
    if (out.source.IsBound(from) && !out.source.IsBound(to)) out.source.Bind(to, out.source(from));
  };
  Stopwatch step;
  // Bodies that meet face to face are repaired as one: the first holds the
  // faces of both, the second is a part of it.
  std::vector<TopoDS_Shape> joined_parts = parts;
  const std::vector<std::pair<int, int>> joins = face_to_face(parts, tol);
  for (const auto& [a, b] : joins) {
    joined_parts[a] = compound_of(joined(faces_of(parts[a]), faces_of(parts[b])));
    joined_parts[b] = TopoDS_Shape();
    auto& ids = info.components[a].face_ids;
    ids.insert(ids.end(), info.components[b].face_ids.begin(), info.components[b].face_ids.end());
  }
  for (size_t k = 0; k < parts.size(); ++k) {
    Component& c = info.components[k];
    const TopoDS_Shape& s = joined_parts[k];
    if (s.IsNull()) continue;  // joined to another body (joins)
    // A body closed with faces back to back inside it (two halves sewn
    // together with both root caps) bounds no volume the fuse can use: it
    // goes through the repair, which takes such pairs out.
    const bool back_to_back = (s.ShapeType() == TopAbs_SOLID || c.closed) && !coincident_pairs(faces_of(s), tol).empty();
    if (s.ShapeType() == TopAbs_SOLID && !back_to_back) {
      c.role = "solid";
      // A solid as read may be invalid (a face turned inside out in its
      // shell): the general fuse would then classify it wrongly and drop
      // what lies outside. Mended first (ShapeFix_Solid orients its shells'
      // faces); a solid it cannot mend goes to the union of meshes.
      TopoDS_Shape solid = s;
      if (!BRepCheck_Analyzer(solid).IsValid()) {
        ShapeFix_Solid fix(TopoDS::Solid(solid));
        fix.Perform();
        const TopoDS_Shape mended = fix.Solid();
        if (!mended.IsNull() && mended.ShapeType() == TopAbs_SOLID && BRepCheck_Analyzer(mended).IsValid()) {
          solid = mended;  // its faces the same, some turned: their sources hold
        } else {
          c.route = "not united: its solid is not valid";
          info.not_united.push_back(static_cast<int>(k) + 1);
          invalid.push_back(s);
          continue;
        }
      }
      solids.push_back(solid);
      solid_component.push_back(static_cast<int>(k));
      continue;
    }
    Repair r;
    if (c.closed && !back_to_back) {
      r.closed = s;
    } else if (s.ShapeType() == TopAbs_FACE && count_free_curves(s) == 0) {
      // One face closed on itself (a body of revolution with poles): its shell.
      TopoDS_Shell shell;
      BRep_Builder b;
      b.MakeShell(shell);
      b.Add(shell, s);
      shell.Closed(true);
      r.closed = shell;
    } else if (s.ShapeType() == TopAbs_SHELL || s.ShapeType() == TopAbs_FACE || back_to_back) {
      // An open shell, or one open face (OpenVSP writes a whole wing or fin
      // as one face, its caps folded onto the chord): sewn pieces go through
      // the repair.
      // Caps built into a skin (OpenVSP's root and tip caps, flat strips
      // folded onto the chord) split off as faces of their own, when that
      // finds caps back to back: two halves' root caps, a pod's tip cap and
      // its strut's root cap. The repair then takes both of each pair out.
      FaceList faces = faces_of(s);
      int folds = 0;
      const TopoDS_Shape split = split_folds(s, kFoldBand * diagonal, follow, folds, true);
      if (folds > 0 && coincident_pairs(faces_of(split), tol).size() > coincident_pairs(faces, tol).size()) {
        faces = faces_of(split);
        info.faces_split_at_folds += folds;
      }
      r = repair_component(faces, tol, diagonal_of(c), half, options.domain.symmetry_axis);
      for (const auto& [f, piece] : r.split) follow(f, piece);
      for (const auto& f : r.kept) follow(f, r.sewn.after(f));
    }
    if (!r.half_open.IsNull()) {
      c.role = "sheet";
      c.route = std::string("half model: open on the plane ") + static_cast<char>('x' + r.half_model_axis) + " = 0";
      c.faces_removed = r.duplicates + r.internal + static_cast<int>(r.sheets.size());
      info.duplicate_faces_removed += r.duplicates;
      info.internal_faces_removed += r.internal;
      info.half_model_axis = r.half_model_axis;
      sheets.push_back(r.half_open);
      sheet_component.push_back(static_cast<int>(k));
      for (const auto& f : r.sheets) loose.push_back(f), loose_component.push_back(static_cast<int>(k));
      continue;
    }
    const std::vector<TopoDS_Shape> closed = r.closed.IsNull() ? std::vector<TopoDS_Shape>() : solids_of(r.closed);
    if (closed.empty()) {
      c.role = "sheet";
      if (gp_Pln plane; flat_disk(s, tol, plane)) flat.emplace_back(static_cast<int>(k), plane);
      sheets.push_back(s);
      sheet_component.push_back(static_cast<int>(k));
      continue;
    }
    c.role = "solid";
    c.faces_removed = r.duplicates + r.internal + static_cast<int>(r.sheets.size());
    c.caps_added = r.caps;
    info.caps_added += r.caps;
    info.duplicate_faces_removed += r.duplicates;
    info.internal_faces_removed += r.internal;
    if (!c.closed || back_to_back) ++info.components_repaired;
    for (const auto& solid : closed) solids.push_back(solid), solid_component.push_back(static_cast<int>(k));
    for (const auto& f : r.sheets) loose.push_back(f), loose_component.push_back(static_cast<int>(k));
  }
  // Flat disks a body passes through (actuator disks) are left out.
  std::vector<TopoDS_Shape> bodies = solids;
  bodies.insert(bodies.end(), invalid.begin(), invalid.end());
  for (const auto& [k, plane] : flat)
    if (pierced(parts[k], plane, bodies, tol)) {
      const auto at = std::find(sheet_component.begin(), sheet_component.end(), k) - sheet_component.begin();
      sheets.erase(sheets.begin() + at);
      sheet_component.erase(sheet_component.begin() + at);
      info.components[k].role = "disk";
      info.components[k].route = "left out: a flat disk a body passes through, no wall";
      info.left_out.push_back(k + 1);
    }
  // A sheet wholly inside a body or on its surface (a wing's planform plane
  // exported as a component of its own, between the skins) bounds no fluid:
  // it is left out. Every one of 9 points spread over each face must be in:
  // a fin reaching out of a body keeps its outer part as a wall.
  const Solids inside(solids, tol);
  for (size_t i = 0; i < sheets.size();) {
    const FaceList faces = faces_of(sheets[i]);
    const bool held = !solids.empty() && !faces.empty() && std::all_of(faces.begin(), faces.end(), [&](const TopoDS_Face& f) {
                        return inside.hold_whole(f, 9);
                      });
    if (!held) {
      ++i;
      continue;
    }
    const int k = sheet_component[i];
    sheets.erase(sheets.begin() + static_cast<long>(i));
    sheet_component.erase(sheet_component.begin() + static_cast<long>(i));
    info.components[k].role = "internal";
    info.components[k].route = "left out: a sheet inside a body";
    info.internal_sheets.push_back(k + 1);
  }
  // Faces taken out of one component may lie inside another one (the plane
  // of the left tail inside the right tail): those are internal too.
  for (size_t i = 0; i < loose.size(); ++i) {
    if (inside.hold(loose[i])) ++info.internal_faces_removed;
    else sheets.push_back(loose[i]), sheet_component.push_back(loose_component[i]);
  }
  info.repair_seconds = step.lap();

  // Components the options send straight to the mesh-level union.
  std::vector<TopoDS_Shape> apart = invalid;
  for (int k : options.mesh_union)
    if (k < 1 || k > static_cast<int>(info.components.size()))
      throw Error("--mesh-union " + std::to_string(k) + ": the model has " + std::to_string(info.components.size()) +
                  " components (sizemesh --info lists them)");
  if (!options.describe_only) {
    std::vector<TopoDS_Shape> kept;
    std::vector<int> kept_component;
    for (size_t i = 0; i < solids.size(); ++i) {
      const int k = solid_component[i];
      if (options.mesh_union_all || std::count(options.mesh_union.begin(), options.mesh_union.end(), k + 1)) {
        info.components[k].route = "not united: --mesh-union asks for a union of meshes";
        info.not_united.push_back(k + 1);
        apart.push_back(solids[i]);
      } else {
        kept.push_back(solids[i]), kept_component.push_back(k);
      }
    }
    solids.swap(kept);
    solid_component.swap(kept_component);
  }
  if (options.describe_only) {
    info.union_skipped = true;
  } else if (solids.size() >= 2) {
    const TopoDS_Shape united =
        unite_solids(solids, solid_component, tol, deadline, meshes_take_over(options), follow, options.progress, info);
    solids.clear();
    for (TopExp_Explorer ex(united, TopAbs_SOLID); ex.More(); ex.Next()) solids.push_back(ex.Current());
  } else if (solids.size() == 1) {
    info.components[solid_component[0]].route = "alone: the only closed component";
  }
  info.union_seconds = step.lap();
  solids.insert(solids.end(), apart.begin(), apart.end());
  TopoDS_Shape result;
  if (!options.describe_only && !sheets.empty() && solids.size() + sheets.size() >= 2) {
    if (options.progress) options.progress("imprinting " + std::to_string(sheets.size()) + " open components");
    result = imprint_sheets(solids, sheets, tol, deadline, follow, info);
    for (int k : sheet_component) {
      if (info.components[k].role == "sheet")
        info.components[k].route = result.IsNull() ? "not united: " + info.fallback : "imprinted";
      if (result.IsNull()) info.not_united.push_back(k + 1);
    }
  }
  if (result.IsNull()) {
    BRep_Builder b;
    TopoDS_Compound all;
    b.MakeCompound(all);
    for (const auto& s : sheets) b.Add(all, s);
    for (const auto& s : solids) b.Add(all, s);
    result = all;
  }
  for (const auto& [a, b] : joins) {
    Component& c = info.components[b];
    c.role = info.components[a].role;
    const std::string& with = info.components[a].route;
    c.route = "one body with component " + std::to_string(a + 1) + " (faces back to back)" + (with.empty() ? "" : ": " + with);
  }
  info.imprint_seconds = step.lap();
  std::sort(info.not_united.begin(), info.not_united.end());
  info.not_united.erase(std::unique(info.not_united.begin(), info.not_united.end()), info.not_united.end());
  // --info stops here: the last splits serve the mesher, and a description
  // of the file has no use for them.
  if (options.describe_only) {
    out.shape = result;
    info.faces_after = static_cast<int>(faces_of(out.shape).size());
    return out;
  }
  // Folds narrower than half the default smallest element become curves.
  int folds = 0;
  out.shape = split_folds(result, kFoldBand * diagonal, follow, folds);
  // Strips too narrow for sewing to keep their corners (some split off at a
  // fold just now) become curves.
  out.shape = collapse_strips(out.shape, 2 * tol, follow, info.strip_faces_collapsed);
  info.faces_split_at_folds += folds;
  // Flat faces on their plane: no region of zero area in their uv.
  out.shape = planar_faces(out.shape, tol, out.source, follow, info.faces_made_planar);
  out.shape = drop_small_loops(out.shape, tol, follow, info.small_loops_dropped);
  info.faces_after = static_cast<int>(faces_of(out.shape).size());
  info.finish_seconds = step.lap();
  return out;
}

}  // namespace sizemesh
