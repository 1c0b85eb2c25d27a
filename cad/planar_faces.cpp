// Faces whose surface is a plane in all but name rebuilt on that plane
// (planar_faces, cad/occt_model.h).
//
// CAD writers export flat caps and root faces as B-splines ruled between two
// curves. Where those curves meet (a wing's root cap at its leading and
// trailing edges) the parametrisation collapses: a front advancing in uv
// folds its triangles over each other there; sewing a cap's two halves along
// their chord, each parametrised its own way, widens the chord's tolerance to
// a sizeable part of the wing (a general fuse then finds everything within
// it in contact); and a Boolean cut at a coincident plane treats the cap as
// a curved face. On the plane itself uv is length, and the same edges bound it.
#include <BRepBuilderAPI_Copy.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepLib.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepTools.hxx>
#include <BRepTools_ReShape.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <Geom_Plane.hxx>
#include <GeomLib_IsPlanarSurface.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <TopTools_DataMapOfShapeInteger.hxx>
#include <TopTools_DataMapOfShapeShape.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopTools_MapOfShape.hxx>

#include <algorithm>
#include <vector>

#include "cad/occt_model.h"
#include "core/off_thread.h"

namespace sizemesh {
namespace {

// The surface normal (du x dv) at the middle of the face's uv box, or false.
bool mid_normal(const TopoDS_Face& f, gp_Dir& n) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  BRepAdaptor_Surface s(f, false);
  for (double t : {0.5, 0.3, 0.7, 0.1, 0.9}) {
    BRepLProp_SLProps p(s, u0 + t * (u1 - u0), v0 + (1 - t) * (v1 - v0), 1, 1e-9);
    if (p.IsNormalDefined()) {
      n = p.Normal();
      return true;
    }
  }
  return false;
}

// The plane through the face's surface over its uv box, when every point of
// a grid there lies within tol of it (least squares: the plane through the
// centroid normal to the direction of least spread). A collapsed
// parametrisation is no obstacle, where OCCT's planarity test throws.
bool fitted_plane(const TopoDS_Face& f, double tol, gp_Pln& plane) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  BRepAdaptor_Surface s(f, false);
  constexpr int n = 12;
  std::vector<Vec3> p;
  Vec3 c = Vec3::Zero();
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const gp_Pnt q = s.Value(u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * j / n);
      p.emplace_back(q.X(), q.Y(), q.Z());
      c += p.back();
    }
  c /= static_cast<double>(p.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& q : p) cov += (q - c) * (q - c).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  if (eig.info() != Eigen::Success || !(eig.eigenvalues()(1) > 0)) return false;  // a line or a point
  const Vec3 normal = eig.eigenvectors().col(0);
  for (const Vec3& q : p)
    if (std::abs((q - c).dot(normal)) > tol) return false;
  plane = gp_Pln(gp_Pnt(c.x(), c.y(), c.z()), gp_Dir(normal.x(), normal.y(), normal.z()));
  return true;
}

// A degenerate edge, or a closed one no longer than `tol`: a point that the
// surface's parametrisation stretched into a line.
bool point_like(const TopoDS_Edge& e, double tol) {
  if (BRep_Tool::Degenerated(e)) return true;
  TopoDS_Vertex v0, v1;
  TopExp::Vertices(e, v0, v1);
  if (v0.IsNull() || !v0.IsSame(v1)) return false;
  BRepAdaptor_Curve c(e);
  return GCPnts_AbscissaPoint::Length(c, tol) <= tol;
}

// True when the face's parametrisation has no area along a line of it: the
// area element |Su x Sv| vanishes on a row's worth of a grid over its uv box.
// With `borders`, the grid's rows and columns include the box's sides (a cap
// ruled between two curves that meet at its ends collapses along both end
// lines); without, it samples cell centres, where a collapse inside the face
// shows.
bool collapses(const TopoDS_Face& f, bool borders) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  BRepAdaptor_Surface s(f, false);
  constexpr int n = 10;
  const int rows = borders ? n + 1 : n;
  const double shift = borders ? 0.0 : 0.5;
  double most = 0;
  std::vector<double> element;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < rows; ++j) {
      gp_Pnt p;
      gp_Vec du, dv;
      s.D1(u0 + (u1 - u0) * (i + shift) / n, v0 + (v1 - v0) * (j + shift) / n, p, du, dv);
      element.push_back(du.Crossed(dv).Magnitude());
      most = std::max(most, element.back());
    }
  return std::count_if(element.begin(), element.end(), [&](double a) { return a <= 1e-9 * most; }) >= rows;
}

// Face f (taken forward) rebuilt on `plane` with its edges, degenerate ones
// and point-like ones left out (a point on a plane is no curve); checked by
// the caller.
TopoDS_Face on_plane(const TopoDS_Face& f, const Handle(Geom_Plane)& plane, double tol) {
  BRep_Builder b;
  TopoDS_Face out;
  b.MakeFace(out, plane, tol);
  for (TopoDS_Iterator w(f.Oriented(TopAbs_FORWARD)); w.More(); w.Next()) {
    if (w.Value().ShapeType() != TopAbs_WIRE) continue;
    TopoDS_Wire wire;
    b.MakeWire(wire);
    int edges = 0;
    for (TopoDS_Iterator e(w.Value()); e.More(); e.Next())
      if (!point_like(TopoDS::Edge(e.Value()), tol)) b.Add(wire, e.Value()), ++edges;
    if (edges == 0) continue;
    wire.Closed(true);
    b.Add(out, wire.Oriented(w.Value().Orientation()));
  }
  TopTools_ListOfShape edges;
  for (TopExp_Explorer e(out, TopAbs_EDGE); e.More(); e.Next()) edges.Append(e.Current());
  BRepLib::BuildPCurveForEdgesOnPlane(edges, out);
  BRepLib::SameParameter(out, tol);
  return out;
}

// Neighbouring faces rebuilt on their plane, cut from one source face and
// lying on one plane (the upper and lower halves of a wing's root cap, split
// at its chord), merged into one: their shared edge, an iso-line of a
// surface that collapsed there, is no curve of the model, and a Boolean cut
// at that plane fails on it. Every other edge is kept.
TopoDS_Shape merge_coplanar(const TopoDS_Shape& shape, const TopTools_DataMapOfShapeInteger& source,
                            const TopTools_MapOfShape& rebuilt, const Follow& follow) {
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  ShapeUpgrade_UnifySameDomain unify(shape, false, true, false);
  int mergeable = 0;
  for (int i = 1; i <= edge_faces.Extent(); ++i) {
    const TopTools_ListOfShape& faces = edge_faces(i);
    bool merge = faces.Extent() == 2;
    int id = -1;
    for (const auto& f : faces) {
      if (!merge) break;
      merge = rebuilt.Contains(f) && source.IsBound(f) && (id < 0 || source(f) == id);
      if (merge) id = source(f);
    }
    if (merge) ++mergeable;
    else unify.KeepShape(edge_faces.FindKey(i));
  }
  if (mergeable == 0) return shape;
  TopoDS_Shape result;
  try {
    unify.Build();
    result = unify.Shape();
  } catch (const Standard_Failure&) {
    return shape;
  }
  if (result.IsNull() || !step_keeps_shape_valid(shape, result)) return shape;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next())
    for (const auto& g : unify.History()->Modified(ex.Current()))
      if (g.ShapeType() == TopAbs_FACE) follow(TopoDS::Face(ex.Current()), TopoDS::Face(g));
  return result;
}

// A side of f of zero length that is no degenerate edge.
bool has_pinched_side(const TopoDS_Face& f, double tol) {
  for (TopExp_Explorer e(f, TopAbs_EDGE); e.More(); e.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    if (!BRep_Tool::Degenerated(edge) && point_like(edge, tol)) return true;
  }
  return false;
}

// The shape with its flat faces whose parametrisation collapses (collapses,
// `borders`) rebuilt on their plane, each checked alone; `replaced` gets
// each (face, result) pair. Returns `shape` when none is. With `pinched`,
// faces with a side of zero length that is no degenerate edge (a cap half
// collapsing at both ends of its chord: no front starts from such a side)
// are taken too, and where OCCT's planarity test throws on them the fitted
// plane judges.
TopoDS_Shape rebuild_flat(const TopoDS_Shape& shape, double tol, bool borders, bool pinched,
                          std::vector<std::pair<TopoDS_Face, TopoDS_Face>>& replaced) {
  Handle(BRepTools_ReShape) reshape = new BRepTools_ReShape;
  std::vector<std::pair<TopoDS_Face, TopoDS_Face>> candidates;
  TopTools_MapOfShape seen;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face f = TopoDS::Face(ex.Current().Oriented(TopAbs_FORWARD));
    if (!seen.Add(f)) continue;
    try {
      const Handle(Geom_Surface) s = BRep_Tool::Surface(f);
      if (s.IsNull() || BRepAdaptor_Surface(f, false).GetType() == GeomAbs_Plane) continue;
      if (!collapses(f, borders) && !(pinched && has_pinched_side(f, tol))) continue;
      // OCCT's planarity test, or where it throws on a collapsed
      // parametrisation, the fitted plane.
      gp_Pln pln;
      bool flat = false;
      try {
        GeomLib_IsPlanarSurface planar(s, tol);
        flat = planar.IsPlanar();
        if (flat) pln = planar.Plan();
      } catch (const Standard_Failure&) {
        flat = pinched && fitted_plane(f, tol, pln);
      }
      if (!flat) continue;
      gp_Dir n;
      if (!mid_normal(f, n)) continue;
      if (pln.Axis().Direction().Dot(n) < 0) pln.SetAxis(pln.Axis().Reversed());
      const TopoDS_Face g = on_plane(f, new Geom_Plane(pln), tol);
      if (g.IsNull()) continue;
      candidates.emplace_back(f, g);
    } catch (const Standard_Failure&) {
      continue;  // the face keeps its surface
    }
  }
  // Each rebuilt face checked alone (BRepCheck's wire self-intersection test
  // of B-spline curves on the plane is the costly part), in parallel, off
  // this thread (core/off_thread.h).
  std::vector<char> valid(candidates.size(), 0);
  off_this_thread(candidates.size(), [&](size_t i) {
    try {
      valid[i] = BRepCheck_Analyzer(candidates[i].second).IsValid();
    } catch (const Standard_Failure&) {
      valid[i] = 0;
    }
  });
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (!valid[i]) continue;
    reshape->Replace(candidates[i].first, candidates[i].second);
    replaced.push_back(candidates[i]);
  }
  if (replaced.empty()) return shape;
  try {
    const TopoDS_Shape result = reshape->Apply(shape);
    if (!result.IsNull()) return result;
  } catch (const Standard_Failure&) {
  }
  replaced.clear();
  return shape;
}

}  // namespace

TopoDS_Shape planar_faces(const TopoDS_Shape& shape, double tol, const TopTools_DataMapOfShapeInteger& source,
                          const Follow& follow, int& rebuilt) {
  rebuilt = 0;
  if (shape.IsNull()) return shape;
  std::vector<std::pair<TopoDS_Face, TopoDS_Face>> replaced;
  const TopoDS_Shape result = rebuild_flat(shape, tol, false, true, replaced);
  if (replaced.empty() || !step_keeps_shape_valid(shape, result)) return shape;
  TopTools_MapOfShape on_planes;
  for (const auto& [f, g] : replaced) follow(f, g), on_planes.Add(g);
  rebuilt = static_cast<int>(replaced.size());
  return merge_coplanar(result, source, on_planes, follow);
}

TopoDS_Shape flat_faces_before_sewing(const TopoDS_Shape& shape, double tol, TopTools_DataMapOfShapeShape& image,
                                      int& rebuilt) {
  rebuilt = 0;
  if (shape.IsNull()) return shape;
  // On a copy: a face rebuilt on its plane shares its edges with its
  // neighbours, and fitting them to the plane changes those edges, which the
  // shape as read (kept when this sewing is not) must not see.
  BRepBuilderAPI_Copy copy(shape, true, false);
  const TopoDS_Shape copied = copy.Shape();
  std::vector<std::pair<TopoDS_Face, TopoDS_Face>> replaced;
  const TopoDS_Shape result = rebuild_flat(copied, tol, true, false, replaced);
  TopTools_DataMapOfShapeShape to_plane;
  for (const auto& [f, g] : replaced) to_plane.Bind(f, g);
  for (const TopAbs_ShapeEnum type : {TopAbs_FACE, TopAbs_SOLID})
    for (TopExp_Explorer ex(shape, type); ex.More(); ex.Next()) {
      const TopoDS_Shape& f = ex.Current();
      if (image.IsBound(f)) continue;
      const TopoDS_Shape c = copy.ModifiedShape(f);
      const TopoDS_Shape forward = c.Oriented(TopAbs_FORWARD);
      image.Bind(f, to_plane.IsBound(forward) ? to_plane(forward).Oriented(c.Orientation()) : c);
    }
  rebuilt = static_cast<int>(replaced.size());
  return result;
}

}  // namespace sizemesh
