// BRepMesh tessellation of the model, copied out of OCCT's triangulations
// (cad/tessellate.h).
#include "cad/tessellate.h"

#include <BRepAdaptor_Curve.hxx>
#include <BRepMesh_Context.hxx>
#include <BRepMesh_EdgeDiscret.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GCPnts_TangentialDeflection.hxx>
#include <Geom_BSplineCurve.hxx>
#include <IMeshData_Edge.hxx>
#include <IMeshData_Model.hxx>
#include <IMeshTools_CurveTessellator.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_ErrorHandler.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include <algorithm>
#include <string>
#include <vector>

#include "cad/occt_model.h"

namespace sizemesh {
namespace {

// One piece of an edge's parameter range: a run of knot spans over which the
// curve moves, or one over which it stands still (all its poles at one point).
struct Piece {
  double a, b;
  bool still;
};

// The edge's range cut at the B-spline knots, neighbouring spans of the same
// kind merged. A span stands still when deg + 2 points of it coincide (its
// coordinates are polynomials of degree deg, rational ones included).
std::vector<Piece> pieces_of(const BRepAdaptor_Curve& c) {
  const double t0 = c.FirstParameter(), t1 = c.LastParameter();
  std::vector<double> cuts = {t0};
  int degree = 1;
  if (c.GetType() == GeomAbs_BSplineCurve) {
    const Handle(Geom_BSplineCurve) b = c.BSpline();
    degree = b->Degree();
    for (int i = 1; i <= b->NbKnots(); ++i)
      if (b->Knot(i) > t0 + Precision::PConfusion() && b->Knot(i) < t1 - Precision::PConfusion())
        cuts.push_back(b->Knot(i));
  }
  cuts.push_back(t1);
  std::vector<Piece> pieces;
  for (size_t i = 1; i < cuts.size(); ++i) {
    const gp_Pnt p0 = c.Value(cuts[i - 1]);
    bool still = true;
    for (int k = 1; k <= degree + 1 && still; ++k)
      still = p0.Distance(c.Value(cuts[i - 1] + (cuts[i] - cuts[i - 1]) * k / (degree + 1))) < Precision::Confusion();
    if (!pieces.empty() && pieces.back().still == still) pieces.back().b = cuts[i];
    else pieces.push_back({cuts[i - 1], cuts[i], still});
  }
  return pieces;
}

// An edge's nodes by tangential deflection over the pieces where its curve
// moves, at BRepMesh's own deflections (half the edge's), and one node for
// each piece where it stands still: at the edge's end when the piece holds
// it, else where the piece starts. OpenVSP closes a sharp trailing edge with
// a knot span standing still. Where a fold split leaves that span at the end
// of a curve, OCCT 7.6's GCPnts_TangentialDeflection moves its last-but-one
// node halfway to the end, into the span, and throws when it checks the chord
// from there (GCPnts_DistFunction draws a line through two equal points);
// BRepMesh then fails every face on that curve.
class StillSpanTessellator : public IMeshTools_CurveTessellator {
 public:
  StillSpanTessellator(const IMeshData::IEdgeHandle& edge, const IMeshTools_Parameters& p) {
    const BRepAdaptor_Curve c(edge->GetEdge());
    const double lin = std::max(0.5 * edge->GetDeflection(), Precision::Confusion());
    const double ang = std::max(0.5 * edge->GetAngularDeflection(), Precision::Angular());
    for (const Piece& piece : pieces_of(c)) {
      if (piece.still) {
        if (t_.empty()) add(piece.a, c.Value(piece.a));
        if (piece.b == c.LastParameter()) {
          if (t_.size() == 1) add(piece.b, c.Value(piece.b));
          t_.back() = piece.b;
        }
        continue;
      }
      GCPnts_TangentialDeflection d(c, piece.a, piece.b, ang, lin, 2, Precision::PConfusion(), p.MinSize);
      for (int i = t_.empty() ? 1 : 2; i <= d.NbPoints(); ++i) add(d.Parameter(i), d.Value(i));
    }
  }
  Standard_Integer PointsNb() const override { return static_cast<int>(t_.size()); }
  Standard_Boolean Value(const Standard_Integer i, gp_Pnt& p, Standard_Real& t) const override {
    p = p_[i - 1];
    t = t_[i - 1];
    return Standard_True;
  }

 private:
  void add(double t, const gp_Pnt& p) {
    t_.push_back(t);
    p_.push_back(p);
  }
  std::vector<double> t_;
  std::vector<gp_Pnt> p_;
};

// BRepMesh's edge discretisation, then StillSpanTessellator on the edges of
// faces it failed on: their polygons, on every face using them, come from the
// same nodes, so the faces are meshed and stay conforming.
class EdgeDiscret : public IMeshTools_ModelAlgo {
 protected:
  Standard_Boolean performInternal(const Handle(IMeshData_Model)& model, const IMeshTools_Parameters& p,
                                   const Message_ProgressRange& range) override {
    Handle(BRepMesh_EdgeDiscret) occt = new BRepMesh_EdgeDiscret;
    if (!occt->Perform(model, p, range)) return Standard_False;
    for (int i = 0; i < model->EdgesNb(); ++i) {
      const IMeshData::IEdgeHandle& edge = model->GetEdge(i);
      if (!edge->IsSet(IMeshData_Failure) || edge->IsFree()) continue;
      edge->Clear(Standard_False);
      try {
        OCC_CATCH_SIGNALS
        BRepMesh_EdgeDiscret::Tessellate3d(edge, new StillSpanTessellator(edge, p), Standard_True);
        BRepMesh_EdgeDiscret::Tessellate2d(edge, Standard_True);
        edge->UnsetStatus(IMeshData_Failure);
      } catch (const Standard_Failure&) {
        edge->Clear(Standard_False);  // still failed: BRepMesh leaves its faces without triangles
      }
    }
    return Standard_True;
  }
};

// BRepMesh_IncrementalMesh(shape, deflection, false, angle, true) with the
// edge discretisation above.
void brepmesh(const TopoDS_Shape& shape, double deflection, double angle) {
  BRepMesh_IncrementalMesh mesher;
  mesher.SetShape(shape);
  IMeshTools_Parameters& p = mesher.ChangeParameters();
  p.Deflection = deflection;
  p.Angle = angle;
  p.Relative = Standard_False;
  p.InParallel = Standard_True;
  Handle(BRepMesh_Context) context = new BRepMesh_Context(p.MeshAlgo);
  context->SetEdgeDiscret(new EdgeDiscret);
  mesher.Perform(context);
}

void run_brepmesh(const Model& model, const BackgroundOptions& options) {
  const double diag = model.info().diagonal();
  const double angle = options.angle_deg * kPi / 180.0;
  const double far = model.info().domain.size;
  if (far > 0) {
    // The far field, many body diagonals across, at a deflection relative
    // to its own size; then the rest (the body and the symmetry plane,
    // which share curves) at the body's. Curves the far field shares with
    // the symmetry plane keep their first discretisation.
    TopoDS_Compound outer, rest;
    BRep_Builder b;
    b.MakeCompound(outer);
    b.MakeCompound(rest);
    for (int f = 1; f <= model.num_faces(); ++f)
      b.Add(model.boundary(f) == Boundary::Farfield ? outer : rest, model.impl().faces(f));
    brepmesh(outer, 10 * options.deflection_rel * far, angle);
    brepmesh(rest, options.deflection_rel * diag, angle);
  } else {
    brepmesh(model.impl().shape, options.deflection_rel * diag, angle);
  }
}

void copy_face(const Model::Impl& m, int f, FaceTessellation& out) {
  const TopoDS_Face face = TopoDS::Face(m.faces(f).Oriented(TopAbs_FORWARD));
  TopLoc_Location loc;
  Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
  if (tri.IsNull() || tri->NbTriangles() == 0 || !tri->HasUVNodes()) return;
  const int n = tri->NbNodes();
  out.xyz.resize(n);
  out.uv.resize(n);
  for (int i = 0; i < n; ++i) {
    const gp_Pnt p = tri->Node(i + 1).Transformed(loc.Transformation());
    out.xyz[i] = Vec3(p.X(), p.Y(), p.Z());
    const gp_Pnt2d uv = tri->UVNode(i + 1);
    out.uv[i] = Vec2(uv.X(), uv.Y());
  }
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
    Handle(Poly_PolygonOnTriangulation) poly = BRep_Tool::PolygonOnTriangulation(e, tri, loc);
    if (poly.IsNull()) continue;
    FaceTessellation::CurveUse use;
    use.curve = m.edges.FindIndex(e);
    const OcctCurve& cd = m.curve_data[use.curve - 1];
    const int k = poly->NbNodes();
    const TColStd_Array1OfInteger& nodes = poly->Nodes();
    const bool has_params = poly->HasParameters();
    for (int i = 0; i < k; ++i) {
      use.nodes.push_back(nodes(nodes.Lower() + i) - 1);
      use.t.push_back(has_params ? poly->Parameter(i + 1) : cd.t0 + (cd.t1 - cd.t0) * i / std::max(1, k - 1));
    }
    out.curves.push_back(std::move(use));
  }
  out.tris.resize(tri->NbTriangles());
  for (int t = 1; t <= tri->NbTriangles(); ++t) {
    int a, b, c;
    tri->Triangle(t).Get(a, b, c);
    out.tris[t - 1] = {a - 1, b - 1, c - 1};
  }
}

}  // namespace

Tessellation tessellate(const Model& model, const BackgroundOptions& options) {
  if (!(options.deflection_rel > 0) || !(options.angle_deg > 0))
    throw Error("tessellation deflection and angle must be positive");
  try {
    run_brepmesh(model, options);
  } catch (const Standard_Failure& e) {
    throw Error(std::string("tessellation failed: ") + e.GetMessageString());
  }
  Tessellation out;
  out.faces.resize(model.num_faces());
  for (int f = 1; f <= model.num_faces(); ++f) copy_face(model.impl(), f, out.faces[f - 1]);
  return out;
}

}  // namespace sizemesh
