// The Model of a sewn file (prepare_model): preparation, flow domain, stable ids, cached per-entity geometry.
#include <BRepAdaptor_Curve.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <Geom2d_Curve.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_DataMapOfShapeInteger.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>

#include <tbb/parallel_for.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "cad/occt_model.h"

namespace sizemesh {
namespace {

// A seam edge of face f across which a surface closed but not periodic
// meets itself: its two parameter curves lie the surface's whole range
// apart in u or v. Recorded as the face's wrap in that direction.
void note_wrap(OcctFace& d, const TopoDS_Edge& e, const TopoDS_Face& f) {
  try {
    double a0, a1, b0, b1, su0, su1, sv0, sv1;
    const Handle(Geom2d_Curve) one = BRep_Tool::CurveOnSurface(e, f, a0, a1);
    const Handle(Geom2d_Curve) other = BRep_Tool::CurveOnSurface(TopoDS::Edge(e.Reversed()), f, b0, b1);
    if (one.IsNull() || other.IsNull()) return;
    d.surface->Bounds(su0, su1, sv0, sv1);
    const gp_Pnt2d p = one->Value(0.5 * (a0 + a1)), q = other->Value(0.5 * (b0 + b1));
    const double range[2] = {su1 - su0, sv1 - sv0}, lo[2] = {su0, sv0}, apart[2] = {q.X() - p.X(), q.Y() - p.Y()};
    const bool closed[2] = {d.surface->IsUClosed() && !d.surface->IsUPeriodic(),
                            d.surface->IsVClosed() && !d.surface->IsVPeriodic()};
    for (int axis = 0; axis < 2; ++axis)
      if (closed[axis] && std::isfinite(range[axis]) && range[axis] > 0 &&
          std::abs(std::abs(apart[axis]) - range[axis]) <= 1e-9 * range[axis]) {
        d.wrap[axis] = range[axis];
        d.wrap_lo[axis] = lo[axis];
      }
  } catch (const Standard_Failure&) {
  }
}

OcctFace make_face_data(const TopoDS_Face& face, double area, const TopTools_IndexedMapOfShape& edges,
                        const std::vector<OcctCurve>& curves) {
  OcctFace d;
  d.reversed = face.Orientation() == TopAbs_REVERSED;
  TopoDS_Face fwd = TopoDS::Face(face.Oriented(TopAbs_FORWARD));
  d.surface = BRep_Tool::Surface(fwd);
  double u0, u1, v0, v1;
  BRepTools::UVBounds(fwd, u0, u1, v0, v1);
  d.uv_bounds = {Vec2(u0, v0), Vec2(u1, v1)};
  if (!d.surface.IsNull()) {
    if (d.surface->IsUPeriodic()) d.period_u = d.surface->UPeriod();
    if (d.surface->IsVPeriodic()) d.period_v = d.surface->VPeriod();
  }
  d.area = area;
  // Boundary loops, outer first, edges in traversal order. The boundary length
  // for the proximity size (paper 3.2.2) leaves out seams and poles: they are
  // not borders of the face.
  TopoDS_Wire outer = BRepTools::OuterWire(fwd);
  std::vector<TopoDS_Wire> wires;
  if (!outer.IsNull()) wires.push_back(outer);
  for (TopExp_Explorer ex(fwd, TopAbs_WIRE); ex.More(); ex.Next())
    if (!ex.Current().IsSame(outer)) wires.push_back(TopoDS::Wire(ex.Current()));
  for (const TopoDS_Wire& w : wires) {
    FaceLoop loop;
    for (BRepTools_WireExplorer wex(w, fwd); wex.More(); wex.Next()) {
      const TopoDS_Edge& e = wex.Current();
      CurveUse use;
      use.curve = edges.FindIndex(e);
      use.reversed = e.Orientation() == TopAbs_REVERSED;
      const bool seam = BRep_Tool::IsClosed(e, fwd);
      use.side = seam && use.reversed ? 1 : 0;
      loop.push_back(use);
      if (!seam && !BRep_Tool::Degenerated(e)) d.boundary_length += curves[use.curve - 1].length;
      if (seam && !d.surface.IsNull()) note_wrap(d, e, fwd);
    }
    if (!loop.empty()) d.loops.push_back(std::move(loop));
  }
  return d;
}

OcctCurve make_curve_data(const TopoDS_Edge& edge_any, const TopoDS_Shape& shape,
                          const TopTools_IndexedMapOfShape& vertices,
                          const TopTools_IndexedMapOfShape& faces,
                          const TopTools_IndexedDataMapOfShapeListOfShape& edge_faces) {
  OcctCurve d;
  TopoDS_Edge edge = TopoDS::Edge(edge_any.Oriented(TopAbs_FORWARD));
  d.degenerated = BRep_Tool::Degenerated(edge);
  BRep_Tool::Range(edge, d.t0, d.t1);
  TopoDS_Vertex v0, v1;
  TopExp::Vertices(edge, v0, v1);
  d.start_point = v0.IsNull() ? 0 : vertices.FindIndex(v0);
  d.end_point = v1.IsNull() ? 0 : vertices.FindIndex(v1);
  if (!d.degenerated) {
    double f, l;
    d.curve = BRep_Tool::Curve(edge, f, l);
    if (!d.curve.IsNull()) d.length = GCPnts_AbscissaPoint::Length(BRepAdaptor_Curve(edge));
  }
  const int k = edge_faces.FindIndex(edge);
  if (k == 0) return d;
  for (const TopoDS_Shape& fs : edge_faces(k)) {
    TopoDS_Face f = TopoDS::Face(fs.Oriented(TopAbs_FORWARD));
    const int fid = faces.FindIndex(f);
    const int sides = BRep_Tool::IsClosed(edge, f) ? 2 : 1;
    for (int side = 0; side < sides; ++side) {
      TopoDS_Edge e = TopoDS::Edge(edge.Oriented(side ? TopAbs_REVERSED : TopAbs_FORWARD));
      double f0, f1;
      OcctPCurve pc;
      pc.face = fid;
      pc.side = side;
      pc.curve = BRep_Tool::CurveOnSurface(e, f, f0, f1);
      if (!pc.curve.IsNull()) d.pcurves.push_back(pc);
    }
  }
  return d;
}

}  // namespace

Model prepare_model(const CadFile& cad_file, const LoadOptions& options) {
  const CadFile::Impl& cad = cad_file.impl();
  ModelInfo info = cad.info;
  auto impl = std::make_shared<Model::Impl>();
  TopTools_IndexedMapOfShape original;
  TopExp::MapShapes(cad.shape, TopAbs_FACE, original);
  info.sewn_faces = original.Extent();
  if (info.sewn_faces == 0) throw Error("the model has no faces");
  PreparedShape prepared;
  try {
    // Unsewn faces are each a component of their own: repair and union need sewing.
    prepared = prepare_shape(cad.shape, original, cad.area, cad.tolerance, info.diagonal(), options, info.preparation);
    info.preparation.faces_made_planar += info.flat_faces_before_sewing;
    info.preparation.edges_made_real = info.degenerate_edges_made_real;
  } catch (const Standard_Failure& e) {
    // The preparation only ever improves the model: without it, mesh what was read.
    prepared = PreparedShape{};
    for (int i = 1; i <= original.Extent(); ++i) prepared.source.Bind(original(i), i);
    prepared.shape = cad.shape;
    info.preparation.fallback = std::string("the preparation failed: ") + e.GetMessageString();
  }
  bbox_diagonal(prepared.shape, info.bbox_min, info.bbox_max);  // the body's: sizes stay relative to it
  TopTools_DataMapOfShapeInteger kind;
  if (options.domain.active()) {
    try {
      prepared.shape = add_flow_domain(prepared.shape, prepared.source, options.domain, info.bbox_min, info.bbox_max,
                                       cad.tolerance, info.domain, kind);
    } catch (const Standard_Failure& e) {
      throw Error(std::string("the flow domain could not be built: ") + e.GetMessageString());
    }
  }
  const TopoDS_Shape& shape = prepared.shape;
  info.free_curves_after_sewing = count_free_curves(shape);

  impl->shape = shape;
  TopExp::MapShapes(shape, TopAbs_FACE, impl->faces);
  TopExp::MapShapes(shape, TopAbs_EDGE, impl->edges);
  TopExp::MapShapes(shape, TopAbs_VERTEX, impl->vertices);
  TopExp::MapShapes(shape, TopAbs_SOLID, impl->solids);
  TopExp::MapShapes(shape, TopAbs_SHELL, impl->shells);
  info.faces = impl->faces.Extent();
  info.curves = impl->edges.Extent();
  info.points = impl->vertices.Extent();
  info.solids = impl->solids.Extent();
  info.shells = impl->shells.Extent();
  if (info.faces == 0) throw Error("the model has no faces");

  impl->source_face.assign(info.faces, 0);
  impl->boundary.assign(info.faces, Boundary::Wall);
  for (int f = 1; f <= info.faces; ++f) {
    if (prepared.source.IsBound(impl->faces(f))) impl->source_face[f - 1] = prepared.source(impl->faces(f));
    if (kind.IsBound(impl->faces(f))) impl->boundary[f - 1] = static_cast<Boundary>(kind(impl->faces(f)));
  }
  std::vector<std::string> original_names(info.sewn_faces + 1);
  for (const auto& [s, name] : cad.names) {
    const int id = original.FindIndex(s);
    if (id > 0) original_names[id] = name;
  }
  impl->face_names.assign(info.faces, "");
  for (int f = 0; f < info.faces; ++f) impl->face_names[f] = original_names[impl->source_face[f]];

  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  try {
    impl->curve_data.resize(info.curves);
    tbb::parallel_for(1, info.curves + 1, [&](int c) {
      impl->curve_data[c - 1] =
          make_curve_data(TopoDS::Edge(impl->edges(c)), shape, impl->vertices, impl->faces, edge_faces);
    });
    std::vector<double> area(info.faces, -1.0);
    tbb::parallel_for(0, info.faces, [&](int f) {
      const TopoDS_Shape& face = impl->faces(f + 1);
      area[f] = cad.area.IsBound(face) ? cad.area(face) : face_area_exact(face, 1e-4);
    });
    impl->face_data.reserve(info.faces);
    for (int f = 1; f <= info.faces; ++f)
      impl->face_data.push_back(make_face_data(TopoDS::Face(impl->faces(f)), area[f - 1], impl->edges, impl->curve_data));
    impl->make_span_tables();
  } catch (const Standard_Failure& e) {
    throw Error(std::string("broken shape: ") + e.GetMessageString());
  }
  impl->info = info;
  return Model(impl);
}

Model model_from_shape(const TopoDS_Shape& shape, ModelInfo info, const LoadOptions& options,
                       const std::vector<std::pair<TopoDS_Shape, std::string>>& names) {
  return prepare_model(sew_shape(shape, info, options, names), options);
}

Model model_from_shape(const TopoDS_Shape& shape, const LoadOptions& options) {
  ModelInfo info;
  info.path = "(built in code)";
  info.format = "shape";
  info.unit = "unknown";
  return model_from_shape(shape, info, options);
}

}  // namespace sizemesh
