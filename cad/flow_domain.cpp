// The flow domain around the body for a volume mesher and a solver: a far
// field (sphere or box) around the prepared body, and the symmetry plane of a
// half model. Every face of the result points into the fluid, as a body's
// outward faces do, so the gap sizing (Geometry::fluid_side) and the writers
// see one convention. Far-field and symmetry faces are new: they have no
// source face and carry their Boundary kind instead.
#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>

#include <cmath>
#include <sstream>

#include "cad/occt_model.h"

namespace sizemesh {
namespace {

constexpr double kMaxFarField = 1000;  // largest far field, in body diagonals

gp_Pnt to_pnt(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
Vec3 to_vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }

// The symmetry plane's coordinate: the one given, else 0 when the body
// reaches it (a full aircraft about y = 0, a half wing rooted there), else
// the body's side nearest to 0.
double plane_at(const FlowDomainOptions& o, const Vec3& lo, const Vec3& hi, double tol) {
  const int a = o.symmetry_axis;
  if (o.symmetry_at_given) return o.symmetry_at;
  if (lo[a] - tol <= 0 && 0 <= hi[a] + tol) return 0;
  return std::abs(lo[a]) < std::abs(hi[a]) ? lo[a] : hi[a];
}

// A point inside the solid, just under the surface of one of its faces: the
// hole a volume mesher leaves empty. Null when none is found.
bool inside_point(const TopoDS_Solid& solid, double diag, double tol, Vec3& out) {
  BRepClass3d_SolidClassifier classify(solid);
  for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& face = TopoDS::Face(ex.Current());
    double u0, u1, v0, v1;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    BRepAdaptor_Surface surface(face);
    for (int i = 1; i < 5; ++i)
      for (int j = 1; j < 5; ++j) {
        const gp_Pnt2d uv(u0 + (u1 - u0) * i / 5, v0 + (v1 - v0) * j / 5);
        if (BRepClass_FaceClassifier(face, uv, tol).State() != TopAbs_IN) continue;
        BRepLProp_SLProps props(surface, uv.X(), uv.Y(), 1, tol);
        if (!props.IsNormalDefined()) continue;
        gp_Dir n = props.Normal();
        if (face.Orientation() == TopAbs_REVERSED) n.Reverse();
        for (double depth : {1e-4, 1e-3, 1e-2}) {
          const gp_Pnt q = props.Value().Translated(gp_Vec(n) * (-depth * diag));
          classify.Perform(q, tol);
          if (classify.State() == TopAbs_IN) return out = to_vec(q), true;
        }
      }
  }
  return false;
}

// The body's closed solids (closed shells made solid).
std::vector<TopoDS_Solid> solids_of(const TopoDS_Shape& body) {
  std::vector<TopoDS_Solid> out;
  for (TopExp_Explorer ex(body, TopAbs_SOLID); ex.More(); ex.Next()) out.push_back(TopoDS::Solid(ex.Current()));
  for (TopExp_Explorer ex(body, TopAbs_SHELL, TopAbs_SOLID); ex.More(); ex.Next())
    if (count_free_curves(ex.Current()) == 0) {
      const TopoDS_Solid s = solid_from_shell(TopoDS::Shell(ex.Current()));
      if (!s.IsNull()) out.push_back(s);
    }
  return out;
}

// The far field's solid: whole, or the half on the kept side of the plane.
TopoDS_Shape farfield_solid(FlowDomainOptions::FarField kind, const Vec3& c, double r, int axis, double side) {
  if (kind == FlowDomainOptions::FarField::Sphere) {
    if (axis < 0) return BRepPrimAPI_MakeSphere(to_pnt(c), r).Solid();
    Vec3 d = Vec3::Zero();
    d[axis] = side;
    const gp_Ax2 frame(to_pnt(c), gp_Dir(d.x(), d.y(), d.z()));
    return BRepPrimAPI_MakeSphere(frame, r, 0.0, kPi / 2).Solid();  // from the plane up to the pole
  }
  Vec3 lo = c - Vec3::Constant(r), hi = c + Vec3::Constant(r);
  if (axis >= 0) (side > 0 ? lo : hi)[axis] = c[axis];
  return BRepPrimAPI_MakeBox(to_pnt(lo), to_pnt(hi)).Solid();
}

// The half space on `side` of the symmetry plane, as a box well past the body.
TopoDS_Shape beyond_plane(const Vec3& lo, const Vec3& hi, int axis, double at, double side) {
  const double pad = (hi - lo).norm();
  Vec3 a = lo - Vec3::Constant(pad), b = hi + Vec3::Constant(pad);
  (side > 0 ? a : b)[axis] = at;
  return BRepPrimAPI_MakeBox(to_pnt(a), to_pnt(b)).Solid();
}

// A planar face lying on the symmetry plane.
bool on_plane(const TopoDS_Face& f, int axis, double at, double tol) {
  if (axis < 0 || BRepAdaptor_Surface(f, false).GetType() != GeomAbs_Plane) return false;
  for (TopExp_Explorer ex(f, TopAbs_VERTEX); ex.More(); ex.Next())
    if (std::abs(BRep_Tool::Pnt(TopoDS::Vertex(ex.Current())).Coord(axis + 1) - at) > tol) return false;
  return true;
}

}  // namespace

TopoDS_Shape add_flow_domain(const TopoDS_Shape& body, TopTools_DataMapOfShapeInteger& source,
                             const FlowDomainOptions& o, const Vec3& lo, const Vec3& hi, double tol,
                             FlowDomain& info, TopTools_DataMapOfShapeInteger& kind) {
  using FF = FlowDomainOptions::FarField;
  const double diag = (hi - lo).norm();
  Vec3 center = 0.5 * (lo + hi);
  const int axis = o.symmetry_axis;
  double side = 1;
  if (axis >= 0) {
    info.symmetry_axis = axis;
    info.symmetry_at = plane_at(o, lo, hi, tol);
    side = hi[axis] - info.symmetry_at >= info.symmetry_at - lo[axis] ? 1.0 : -1.0;
    center[axis] = info.symmetry_at;
    if (!(lo[axis] - tol <= info.symmetry_at && info.symmetry_at <= hi[axis] + tol)) {
      std::ostringstream msg;
      msg << "the symmetry plane " << static_cast<char>('x' + axis) << " = " << info.symmetry_at
          << " does not touch the body, which spans " << lo[axis] << " to " << hi[axis];
      throw Error(msg.str());
    }
  }
  const bool closed_body = count_free_curves(body) == 0;
  if (axis >= 0 && !closed_body)
    throw Error("a symmetry plane needs a closed body, and this one has free curves (see --info)");
  TopoDS_Shape domain;
  if (o.farfield != FF::None) {
    info.farfield = o.farfield == FF::Sphere ? "sphere" : "box";
    info.center = center;
    info.size = o.size > 0 ? o.size : 20 * diag;
    info.element_size = o.element_size > 0 ? o.element_size : info.size / 10;
    // The far field must hold the whole (kept) bounding box.
    double need = 0;
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner((k & 1 ? hi : lo).x(), (k & 2 ? hi : lo).y(), (k & 4 ? hi : lo).z());
      need = std::max(need, o.farfield == FF::Sphere ? (corner - center).norm() : (corner - center).cwiseAbs().maxCoeff());
    }
    // Beyond that the far field's tessellation, with the body's tolerances,
    // costs more than the rest; CFD far fields are 20 to 100 lengths out.
    if (!(info.size <= kMaxFarField * diag)) {
      std::ostringstream msg;
      msg << "the far field (size " << info.size << ") is more than " << kMaxFarField << " body diagonals ("
          << kMaxFarField * diag << ") across: give a smaller --farfield-size";
      throw Error(msg.str());
    }
    if (!(info.size > 1.01 * need)) {
      std::ostringstream msg;
      msg << "the far field (size " << info.size << ") does not enclose the body: give --farfield-size above "
          << 1.01 * need;
      throw Error(msg.str());
    }
    domain = farfield_solid(o.farfield, center, info.size, axis, side);
    if (closed_body)
      for (const TopoDS_Solid& s : solids_of(body)) {
        Vec3 p;
        if (inside_point(s, diag, tol, p)) info.inside_points.push_back(p);
      }
  }

  TopoDS_Shape result;
  if (axis < 0) {
    // The far field around the body: its shell turned to face the fluid inside it.
    TopoDS_Compound c;
    BRep_Builder b;
    b.MakeCompound(c);
    b.Add(c, body);
    for (TopExp_Explorer ex(domain, TopAbs_SHELL); ex.More(); ex.Next()) b.Add(c, ex.Current().Reversed());
    result = c;
  } else {
    // The half space is cut away from the body, or the body from the half far field.
    const bool around = !domain.IsNull();
    BRepAlgoAPI_Cut cut;
    TopTools_ListOfShape args, tools;
    args.Append(around ? domain : body);
    tools.Append(around ? body : beyond_plane(lo, hi, axis, info.symmetry_at, -side));
    cut.SetArguments(args);
    cut.SetTools(tools);
    cut.SetRunParallel(true);
    cut.SetFuzzyValue(tol);
    cut.Build();
    if (!cut.IsDone() || cut.HasErrors() || cut.Shape().IsNull())
      throw Error("the body could not be cut at the symmetry plane");
    // Body faces keep their source ids through the cut.
    TopTools_DataMapOfShapeInteger kept;
    for (TopExp_Explorer ex(body, TopAbs_FACE); ex.More(); ex.Next()) {
      const TopoDS_Shape& f = ex.Current();
      if (!source.IsBound(f)) continue;
      const int id = source(f);
      const TopTools_ListOfShape& pieces = cut.Modified(f);
      for (const auto& p : pieces) kept.Bind(p, id);
      if (pieces.IsEmpty() && !cut.IsDeleted(f)) kept.Bind(f, id);
    }
    source = kept;
    result = cut.Shape();
    if (around) {  // the domain's faces point out of the fluid: turn them
      TopoDS_Compound c;
      BRep_Builder b;
      b.MakeCompound(c);
      for (TopExp_Explorer ex(result, TopAbs_SHELL); ex.More(); ex.Next()) b.Add(c, ex.Current().Reversed());
      result = c;
    }
  }
  for (TopExp_Explorer ex(result, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& f = TopoDS::Face(ex.Current());
    if (kind.IsBound(f)) continue;
    if (on_plane(f, axis, info.symmetry_at, 10 * tol)) {
      kind.Bind(f, static_cast<int>(Boundary::Symmetry));
      ++info.symmetry_faces;
    } else if (!source.IsBound(f)) {
      kind.Bind(f, static_cast<int>(Boundary::Farfield));
      ++info.farfield_faces;
    }
  }
  return result;
}

}  // namespace sizemesh
