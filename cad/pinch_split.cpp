// Faces pinched along a slit (split_pinched, cad/occt_model.h).
//
// OpenVSP writes a wing's upper and lower skin as one B-spline face; where
// the tip has zero thickness the face's boundary runs out along the tip chord
// and back along the same line, as two coincident edges of the one face, or
// as one closed edge that folds back on itself.
// Sewing joins edges of different faces only, so the slit stays open (and an
// internal planform plane may be sewn to one side of it instead). Split
// between the two edges, along the parameter line through the point where
// they meet, the face becomes two whose edges along the slit sewing joins.
// A fuselage whose end section has zero width but some height is the same
// slit, written as a degenerated edge (a point) that the surface maps onto
// the line, up and back down: made a real edge first
// (real_degenerate_edges), it is split at each turn.
#include <BRepAdaptor_Curve.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepLib.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Geom_Surface.hxx>
#include <ShapeBuild_ReShape.hxx>
#include <Geom2d_Curve.hxx>
#include <Precision.hxx>
#include <ShapeExtend.hxx>
#include <ShapeFix_Shape.hxx>
#include <ShapeUpgrade_FaceDivide.hxx>
#include <ShapeUpgrade_ShapeDivide.hxx>
#include <ShapeUpgrade_SplitSurface.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_HSequenceOfReal.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Vertex.hxx>

#include <algorithm>
#include <vector>

#include "cad/occt_model.h"

namespace sizemesh {
namespace {

// Splits the surface at one parameter value, u or v.
class ParamSplitter : public ShapeUpgrade_SplitSurface {
 public:
  ParamSplitter(bool along_u, double t) : along_u_(along_u), t_(t) {}
  void Compute(const Standard_Boolean /*segment*/) override {
    const Handle(TColStd_HSequenceOfReal)& values = along_u_ ? myUSplitValues : myVSplitValues;
    const double lo = values->Value(1), hi = values->Value(values->Length());
    const double eps = 1e-6 * (hi - lo);
    if (!(t_ > lo + eps && t_ < hi - eps)) return;
    int i = 1;
    while (i <= values->Length() && values->Value(i) < t_) ++i;
    values->InsertBefore(i, t_);
    myStatus |= ShapeExtend::EncodeStatus(ShapeExtend_DONE1);
  }

 private:
  bool along_u_;
  double t_;
};

// Distance from p to the edge's curve.
double distance_to(const gp_Pnt& p, const TopoDS_Edge& e) {
  BRepExtrema_DistShapeShape d(BRepBuilderAPI_MakeVertex(p).Vertex(), e);
  return d.IsDone() && d.NbSolution() > 0 ? d.Value() : Precision::Infinite();
}

// True when edges a and b run along the same line: both ends within tol,
// and points along each within tol of the other (the two may be
// parametrised differently).
bool coincident(const TopoDS_Edge& a, const TopoDS_Edge& b, double tol) {
  TopoDS_Vertex a0, a1, b0, b1;
  TopExp::Vertices(a, a0, a1);
  TopExp::Vertices(b, b0, b1);
  if (a0.IsNull() || a1.IsNull() || b0.IsNull() || b1.IsNull()) return false;
  const gp_Pnt pa0 = BRep_Tool::Pnt(a0), pa1 = BRep_Tool::Pnt(a1), pb0 = BRep_Tool::Pnt(b0), pb1 = BRep_Tool::Pnt(b1);
  if (pa0.Distance(pa1) <= tol) return false;  // a closed edge is no slit
  const bool same = pa0.Distance(pb0) <= tol && pa1.Distance(pb1) <= tol;
  const bool reversed = pa0.Distance(pb1) <= tol && pa1.Distance(pb0) <= tol;
  if (!same && !reversed) return false;
  for (const auto& [from, to] : {std::pair{&a, &b}, std::pair{&b, &a}}) {
    BRepAdaptor_Curve c(*from);
    for (double s : {0.25, 0.5, 0.75})
      if (distance_to(c.Value(c.FirstParameter() + s * (c.LastParameter() - c.FirstParameter())), *to) > tol)
        return false;
  }
  return true;
}

// True when the parameter line (u = t when along_u, else v = t) crosses f's
// uv box strictly inside, not at its border.
bool strictly_inside(const TopoDS_Face& f, bool along_u, double t) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  const double lo = along_u ? u0 : v0, hi = along_u ? u1 : v1;
  const double eps = 1e-6 * (hi - lo);
  return t > lo + eps && t < hi - eps;
}

// The (u or v, value) to split face f at between its coincident edges a and
// b: the parameter line through the end they share in uv, across the
// direction they run in. False when there is none inside the face.
bool split_line(const TopoDS_Face& f, const TopoDS_Edge& a, const TopoDS_Edge& b, bool& along_u, double& t) {
  double fa, la, fb, lb;
  const Handle(Geom2d_Curve) ca = BRep_Tool::CurveOnSurface(a, f, fa, la);
  const Handle(Geom2d_Curve) cb = BRep_Tool::CurveOnSurface(b, f, fb, lb);
  if (ca.IsNull() || cb.IsNull()) return false;
  const gp_Pnt2d ends_a[2] = {ca->Value(fa), ca->Value(la)}, ends_b[2] = {cb->Value(fb), cb->Value(lb)};
  double best = Precision::Infinite();
  gp_Pnt2d shared;
  for (const auto& p : ends_a)
    for (const auto& q : ends_b)
      if (p.Distance(q) < best) best = p.Distance(q), shared = p;
  const gp_Vec2d run(ends_a[0], ends_a[1]);
  along_u = std::abs(run.X()) >= std::abs(run.Y());  // edges along u: split at a u value
  t = along_u ? shared.X() : shared.Y();
  return strictly_inside(f, along_u, t);
}

// Distance from p to the polyline `line`.
double distance_to(const gp_Pnt& p, const std::vector<gp_Pnt>& line) {
  double best = Precision::Infinite();
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const gp_Vec ab(line[i], line[i + 1]), ap(line[i], p);
    const double len2 = ab.SquareMagnitude();
    const double t = len2 > 0 ? std::clamp(ap.Dot(ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, p.Distance(line[i].Translated(t * ab)));
  }
  return best;
}

// A closed edge that runs out and back along itself (one edge for both
// sides of a slit): true with the parameter where it turns back.
bool folded(const TopoDS_Edge& e, double tol, double& turn) {
  TopoDS_Vertex v0, v1;
  TopExp::Vertices(e, v0, v1);
  if (v0.IsNull() || !v0.IsSame(v1)) return false;
  BRepAdaptor_Curve c(e);
  const double t0 = c.FirstParameter(), t1 = c.LastParameter();
  constexpr int n = 64;
  const gp_Pnt start = c.Value(t0);
  int far = 0;
  std::vector<gp_Pnt> p(n + 1);
  for (int i = 0; i <= n; ++i) {
    p[i] = c.Value(t0 + (t1 - t0) * i / n);
    if (p[i].Distance(start) > p[far].Distance(start)) far = i;
  }
  if (far == 0 || far == n || p[far].Distance(start) <= 10 * tol) return false;
  const std::vector<gp_Pnt> out(p.begin(), p.begin() + far + 1), back(p.begin() + far, p.end());
  for (int i = 0; i <= far; ++i)
    if (distance_to(p[i], back) > tol) return false;
  for (int i = far; i <= n; ++i)
    if (distance_to(p[i], out) > tol) return false;
  turn = t0 + (t1 - t0) * far / n;
  return true;
}

// True when edge e, closed or not, turns straight back along itself inside
// its range (a section collapsed onto a line runs up it and back down):
// `turn` the parameter of the first such reversal, the samples on either
// side of it within tol of the other side's.
bool reverses(const TopoDS_Edge& e, double tol, double& turn) {
  BRepAdaptor_Curve c(e);
  const double t0 = c.FirstParameter(), t1 = c.LastParameter();
  constexpr int n = 128, side = 6;
  std::vector<gp_Pnt> p(n + 1);
  for (int i = 0; i <= n; ++i) p[i] = c.Value(t0 + (t1 - t0) * i / n);
  for (int i = side; i + side <= n; ++i) {
    const gp_Vec a(p[i - 1], p[i]), b(p[i], p[i + 1]);
    if (!(a.Magnitude() > 0.1 * tol) || !(b.Magnitude() > 0.1 * tol) || !(a.Dot(b) < -0.9 * a.Magnitude() * b.Magnitude()))
      continue;
    const std::vector<gp_Pnt> before(p.begin() + i - side, p.begin() + i + 1), after(p.begin() + i, p.begin() + i + side + 1);
    const double reach = std::min(p[i].Distance(p[i - side]), p[i].Distance(p[i + side]));
    bool back = reach > 10 * tol;
    for (int k = 1; k <= side && back; ++k) {
      // Within the shorter side's reach, each side lies on the other.
      if (p[i - k].Distance(p[i]) <= reach) back = distance_to(p[i - k], after) <= tol;
      if (back && p[i + k].Distance(p[i]) <= reach) back = distance_to(p[i + k], before) <= tol;
    }
    if (!back) continue;
    turn = t0 + (t1 - t0) * i / n;
    return true;
  }
  return false;
}

// The (u or v, value) to split face f at across a folded edge: the parameter
// line through its turning point, across the direction it runs in.
bool split_line_at_turn(const TopoDS_Face& f, const TopoDS_Edge& e, double turn, bool& along_u, double& t) {
  double f0, f1;
  const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, f, f0, f1);
  if (pc.IsNull()) return false;
  const gp_Pnt2d a = pc->Value(f0), m = pc->Value(turn);
  along_u = std::abs(m.X() - a.X()) >= std::abs(m.Y() - a.Y());
  t = along_u ? m.X() : m.Y();
  return strictly_inside(f, along_u, t);
}

// The pieces of f split at (along_u, t), or empty when that fails.
std::vector<TopoDS_Face> divided(const TopoDS_Face& f, bool along_u, double t) {
  Handle(ShapeUpgrade_FaceDivide) face_tool = new ShapeUpgrade_FaceDivide;
  face_tool->SetSplitSurfaceTool(new ParamSplitter(along_u, t));
  ShapeUpgrade_ShapeDivide divide(f);
  divide.SetSplitFaceTool(face_tool);
  divide.SetSurfaceSegmentMode(true);
  if (!divide.Perform() || !divide.Status(ShapeExtend_DONE)) return {};
  const TopoDS_Shape result = divide.Result();
  if (result.IsNull()) return {};
  BRepLib::SameParameter(result, Precision::Confusion(), true);
  std::vector<TopoDS_Face> pieces;
  // A piece whose new vertices need wider tolerances than the division gave
  // them (a tip of zero thickness) is made valid by the shape healing.
  for (TopExp_Explorer ex(result, TopAbs_FACE); ex.More(); ex.Next()) {
    TopoDS_Shape piece = ex.Current();
    if (!BRepCheck_Analyzer(piece).IsValid()) {
      ShapeFix_Shape fix(piece);
      fix.Perform();
      piece = fix.Shape();
      if (piece.IsNull() || piece.ShapeType() != TopAbs_FACE || !BRepCheck_Analyzer(piece).IsValid()) return {};
    }
    pieces.push_back(TopoDS::Face(piece));
  }
  return pieces.size() > 1 ? pieces : std::vector<TopoDS_Face>{};
}

}  // namespace

TopoDS_Shape real_degenerate_edges(const TopoDS_Shape& shape, double tol, int& made) {
  made = 0;
  ShapeBuild_ReShape reshape;
  for (TopExp_Explorer fx(shape, TopAbs_FACE); fx.More(); fx.Next()) {
    const TopoDS_Face& f = TopoDS::Face(fx.Current());
    for (TopExp_Explorer ex(f, TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
      if (!BRep_Tool::Degenerated(e)) continue;
      try {
        double a, b;
        const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, f, a, b);
        TopLoc_Location at;
        const Handle(Geom_Surface) surface = BRep_Tool::Surface(f, at);
        if (pc.IsNull() || surface.IsNull() || !at.IsIdentity()) continue;
        Bnd_Box image;
        for (int k = 0; k <= 32; ++k) {
          const gp_Pnt2d uv = pc->Value(a + (b - a) * k / 32);
          image.Add(surface->Value(uv.X(), uv.Y()));
        }
        if (!(std::sqrt(image.SquareExtent()) > 100 * tol)) continue;
        TopoDS_Vertex v0, v1;
        TopExp::Vertices(e, v0, v1);
        BRepBuilderAPI_MakeEdge edge(pc, surface, v0, v1, a, b);
        if (!edge.IsDone()) continue;
        TopoDS_Edge real = edge.Edge();
        if (!BRepLib::BuildCurve3d(real)) continue;
        BRep_Builder().UpdateEdge(real, BRep_Tool::Tolerance(e) > tol ? BRep_Tool::Tolerance(e) : tol);
        real.Orientation(e.Orientation());
        reshape.Replace(e, real);
        ++made;
      } catch (const Standard_Failure&) {
        continue;
      }
    }
  }
  return made > 0 ? reshape.Apply(shape) : shape;
}

std::vector<TopoDS_Face> split_pinched(const std::vector<TopoDS_Face>& faces, double tol,
                                       std::vector<std::pair<TopoDS_Face, TopoDS_Face>>& pieces, int depth) {
  std::vector<TopoDS_Face> out;
  for (const TopoDS_Face& f : faces) {
    std::vector<TopoDS_Face> split;
    try {
      TopTools_IndexedMapOfShape edges;
      TopExp::MapShapes(f, TopAbs_EDGE, edges);
      for (int i = 1; i <= edges.Extent() && split.empty(); ++i)
        for (int j = i + 1; j <= edges.Extent() && split.empty(); ++j) {
          const TopoDS_Edge& a = TopoDS::Edge(edges(i));
          const TopoDS_Edge& b = TopoDS::Edge(edges(j));
          if (BRep_Tool::Degenerated(a) || BRep_Tool::Degenerated(b) || !coincident(a, b, tol)) continue;
          bool along_u;
          double t;
          if (split_line(f, a, b, along_u, t)) split = divided(f, along_u, t);
        }
      for (int i = 1; i <= edges.Extent() && split.empty(); ++i) {
        const TopoDS_Edge& e = TopoDS::Edge(edges(i));
        double turn, t;
        bool along_u;
        if (BRep_Tool::Degenerated(e) || BRep_Tool::IsClosed(e, f) || !(folded(e, tol, turn) || reverses(e, tol, turn)))
          continue;
        if (split_line_at_turn(f, e, turn, along_u, t)) split = divided(f, along_u, t);
      }
    } catch (const Standard_Failure&) {
      split.clear();
    }
    if (split.empty()) {
      out.push_back(f);
      continue;
    }
    // A boundary that folds more than once (a section collapsed onto a
    // line runs up it and back down) is split again in its pieces.
    std::vector<std::pair<TopoDS_Face, TopoDS_Face>> within;
    if (depth < 4) split = split_pinched(split, tol, within, depth + 1);
    for (const TopoDS_Face& p : split) {
      pieces.emplace_back(f, p);
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace sizemesh
