// Pieces of a face divided at its folds (cad/fold_pieces.h): collapsed strips cut off, folded-back borders cut.
#include "cad/fold_pieces.h"

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Precision.hxx>
#include <ShapeFix_Shape.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <cmath>
#include <limits>

#include "cad/knot_lines.h"
#include "cad/occt_model.h"  // face_area_exact

namespace sizemesh::detail {

std::vector<TopoDS_Face> rebuild_piece(const TopoDS_Face& piece, double tol) {
  Handle(Geom_Surface) surface = BRep_Tool::Surface(piece);
  if (auto trimmed = Handle(Geom_RectangularTrimmedSurface)::DownCast(surface)) surface = trimmed->BasisSurface();
  const Handle(Geom_BSplineSurface) b = Handle(Geom_BSplineSurface)::DownCast(surface);
  if (b.IsNull()) return {piece};
  double u0, u1, v0, v1;
  BRepTools::UVBounds(piece, u0, u1, v0, v1);
  // Bounded by its domain's borders alone: every edge runs along one.
  const double eu = 1e-7 * (u1 - u0), ev = 1e-7 * (v1 - v0);
  for (TopExp_Explorer ex(piece, TopAbs_EDGE); ex.More(); ex.Next()) {
    double f, l;
    const Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(TopoDS::Edge(ex.Current()), piece, f, l);
    if (c.IsNull()) return {piece};
    bool on[4] = {true, true, true, true};
    for (double t : {f, 0.5 * (f + l), l}) {
      const gp_Pnt2d p = c->Value(t);
      on[0] = on[0] && std::abs(p.X() - u0) <= eu, on[1] = on[1] && std::abs(p.X() - u1) <= eu;
      on[2] = on[2] && std::abs(p.Y() - v0) <= ev, on[3] = on[3] && std::abs(p.Y() - v1) <= ev;
    }
    if (!(on[0] || on[1] || on[2] || on[3])) return {piece};
  }
  double range[2][2] = {{u0, u1}, {v0, v1}};
  bool changed = false;
  for (int d = 0; d < 2; ++d) {
    const bool along_u = d == 0;
    const double t0 = range[d][0], t1 = range[d][1], lo = along_u ? v0 : u0, hi = along_u ? v1 : u1;
    for (const double t : knots_inside(*b, along_u, t0, t1)) {
      if (t > range[d][0] && collapsed_strip(*b, along_u, t0, t, lo, hi, tol)) range[d][0] = t, changed = true;
      if (t < range[d][1] && collapsed_strip(*b, along_u, t, t1, lo, hi, tol))
        range[d][1] = std::min(range[d][1], t), changed = true;
    }
  }
  if (!(range[0][0] < range[0][1]) || !(range[1][0] < range[1][1])) return {piece};
  // A cut in u where a border v = const folds back, and in v where a border u = const does.
  std::vector<double> cuts[2] = {{range[0][0]}, {range[1][0]}};
  for (int d = 0; d < 2; ++d) {
    const bool along_u = d == 0;  // the cut's parameter is u; the borders are v = const
    const double t0 = range[d][0], t1 = range[d][1];
    double best_gap = std::numeric_limits<double>::infinity(), best = t0;
    for (const double t : knots_inside(*b, along_u, t0, t1)) {
      for (double c : {range[1 - d][0], range[1 - d][1]}) {
        const double gap = fold_back_gap(*b, !along_u, c, t0, t, t1, tol);
        if (gap <= tol && gap < best_gap) best_gap = gap, best = t;
      }
    }
    if (best_gap <= tol) cuts[d].push_back(best), changed = true;
    cuts[d].push_back(t1);
  }
  if (!changed) return {piece};
  std::vector<TopoDS_Face> out;
  for (size_t i = 0; i + 1 < cuts[0].size(); ++i)
    for (size_t j = 0; j + 1 < cuts[1].size(); ++j) {
      // A segment of its own, as the division's pieces have: the face's box
      // is its poles'.
      Handle(Geom_BSplineSurface) segment = Handle(Geom_BSplineSurface)::DownCast(b->Copy());
      segment->Segment(cuts[0][i], cuts[0][i + 1], cuts[1][j], cuts[1][j + 1]);
      BRepBuilderAPI_MakeFace make(segment, Precision::Confusion());
      if (!make.IsDone() || !BRepCheck_Analyzer(make.Face()).IsValid()) return {piece};
      TopoDS_Face f = make.Face();
      f.Orientation(piece.Orientation());
      out.push_back(f);
    }
  return out;
}

bool empty(const TopoDS_Face& piece, double whole_area) { return face_area_exact(piece) <= 1e-9 * whole_area; }

bool empty_piece(const TopoDS_Face& f, const std::vector<TopoDS_Face>& pieces) {
  const double whole = face_area_exact(f);
  return std::any_of(pieces.begin(), pieces.end(), [&](const TopoDS_Face& piece) { return empty(piece, whole); });
}

TopoDS_Face healed(const TopoDS_Face& piece) {
  if (BRepCheck_Analyzer(piece).IsValid()) return piece;
  ShapeFix_Shape fix(piece);
  fix.Perform();
  const TopoDS_Shape out = fix.Shape();
  if (out.IsNull() || out.ShapeType() != TopAbs_FACE || !BRepCheck_Analyzer(out).IsValid()) return {};
  return TopoDS::Face(out);
}

}  // namespace sizemesh::detail
