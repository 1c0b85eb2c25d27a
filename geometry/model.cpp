// Model: sewing, stable ids, cached per-entity geometry, and the Geometry interface.
#include <BRepAdaptor_Curve.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepLib.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <Geom2d_Curve.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GProp_GProps.hxx>
#include <GeomLProp_CLProps.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_DataMapOfShapeReal.hxx>
#include <TopTools_DataMapOfShapeShape.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <ShapeBuild_ReShape.hxx>

#include <tbb/parallel_for.h>

#include <cmath>

#include "geometry/occt_model.h"

namespace sizemesh {
namespace {

Vec3 to_vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
Vec3 to_vec(const gp_Vec& v) { return {v.X(), v.Y(), v.Z()}; }

}  // namespace

// Curves bounding exactly one face side (seams and degenerate curves excluded).
int count_free_curves(const TopoDS_Shape& shape) {
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  int free = 0;
  for (int i = 1; i <= edge_faces.Extent(); ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(edge_faces.FindKey(i));
    if (BRep_Tool::Degenerated(e)) continue;
    const auto& faces = edge_faces(i);
    if (faces.Extent() == 1 && !BRep_Tool::IsClosed(e, TopoDS::Face(faces.First()))) ++free;
  }
  return free;
}

bool step_keeps_shape_valid(const TopoDS_Shape& before, const TopoDS_Shape& after) {
  if (count_free_curves(before) == 0 && count_free_curves(after) != 0) return false;
  TopTools_IndexedMapOfShape old;
  TopExp::MapShapes(before, TopAbs_FACE, old);
  TopoDS_Compound fresh;
  BRep_Builder b;
  b.MakeCompound(fresh);
  bool any = false;
  for (TopExp_Explorer ex(after, TopAbs_FACE); ex.More(); ex.Next())
    if (!old.Contains(ex.Current())) b.Add(fresh, ex.Current()), any = true;
  return !any || BRepCheck_Analyzer(fresh, true, true).IsValid();
}

TopoDS_Solid solid_from_shell(const TopoDS_Shell& shell) {
  BRepBuilderAPI_MakeSolid make(shell);
  if (!make.IsDone()) return {};
  TopoDS_Solid solid = make.Solid();
  BRepLib::OrientClosedSolid(solid);
  return solid;
}

double bbox_diagonal(const TopoDS_Shape& shape, Vec3& lo, Vec3& hi) {
  Bnd_Box box;
  BRepBndLib::Add(shape, box, false);
  if (box.IsVoid()) throw Error("the shape has no extent");
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  lo = {x0, y0, z0};
  hi = {x1, y1, z1};
  const double diag = (hi - lo).norm();
  // Corrupt coordinates, or a model no mesh size can be derived from.
  if (!std::isfinite(diag) || !(diag > 1e-9) || diag > 1e12)
    throw Error("the model's bounding box is unusable (diagonal " + std::to_string(diag) +
                " file units; valid models span 1e-9 to 1e12)");
  return diag;
}

namespace {

// Sewing returns shells; closed ones become solids again so the model keeps its volumes.
TopoDS_Shape solids_from_closed_shells(const TopoDS_Shape& sewn) {
  if (TopExp_Explorer(sewn, TopAbs_SOLID).More()) return sewn;
  TopoDS_Compound out;
  BRep_Builder b;
  b.MakeCompound(out);
  bool any_solid = false;
  for (TopExp_Explorer ex(sewn, TopAbs_SHELL); ex.More(); ex.Next()) {
    const TopoDS_Shell& shell = TopoDS::Shell(ex.Current());
    if (BRep_Tool::IsClosed(shell)) {
      const TopoDS_Solid solid = solid_from_shell(shell);
      if (!solid.IsNull()) {
        b.Add(out, solid);
        any_solid = true;
        continue;
      }
    }
    b.Add(out, shell);
  }
  for (TopExp_Explorer ex(sewn, TopAbs_FACE, TopAbs_SHELL); ex.More(); ex.Next()) b.Add(out, ex.Current());
  return any_solid ? TopoDS_Shape(out) : sewn;
}

// Area by OCCT's fixed-order rule, or (relative_eps > 0) adaptively to that
// relative accuracy: for faces the preparation made (union pieces, faces split
// or with split edges), where the fixed rule can be off by a few percent.
double face_area_exact(const TopoDS_Shape& face, double relative_eps = 0) {
  GProp_GProps props;
  if (relative_eps > 0) BRepGProp::SurfaceProperties(face, props, relative_eps);
  else BRepGProp::SurfaceProperties(face, props);
  return std::abs(props.Mass());
}

// Exact areas of the faces in `faces`, computed in parallel (the costliest part of loading).
std::vector<double> face_areas(const TopTools_IndexedMapOfShape& faces) {
  std::vector<double> area(faces.Extent());
  tbb::parallel_for(0, faces.Extent(), [&](int i) { area[i] = face_area_exact(faces(i + 1)); });
  return area;
}

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

// Faces of zero area (caps collapsed to a line or point) cannot carry a mesh.
// Faces are looked up in `area` (exact areas of the shape's faces) and
// recorded there for reuse.
TopoDS_Shape remove_zero_area_faces(const TopoDS_Shape& shape, double diagonal, int& removed,
                                    TopTools_DataMapOfShapeReal& area) {
  Handle(ShapeBuild_ReShape) reshape = new ShapeBuild_ReShape;
  removed = 0;
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  const std::vector<double> a = face_areas(faces);
  for (int i = 1; i <= faces.Extent(); ++i) {
    area.Bind(faces(i), a[i - 1]);
    if (a[i - 1] <= 1e-14 * diagonal * diagonal) {
      reshape->Remove(faces(i));
      ++removed;
    }
  }
  return removed ? reshape->Apply(shape) : shape;
}

}  // namespace

CadFile sew_shape(const TopoDS_Shape& shape_in, ModelInfo info, const LoadOptions& options,
                  const std::vector<std::pair<TopoDS_Shape, std::string>>& names) {
  auto cad = std::make_shared<CadFile::Impl>();
  TopoDS_Shape shape = shape_in;
  const double diag = bbox_diagonal(shape, info.bbox_min, info.bbox_max);
  shape = real_degenerate_edges(shape, options.sewing_tolerance_rel * diag, info.degenerate_edges_made_real);
  info.free_curves_before_sewing = count_free_curves(shape);
  {
    TopTools_IndexedMapOfShape fm;
    TopExp::MapShapes(shape, TopAbs_FACE, fm);
    info.faces_before_sewing = fm.Extent();
  }
  cad->tolerance = options.sewing_tolerance_rel * diag;
  if (!(cad->tolerance > 0) || !std::isfinite(cad->tolerance)) throw Error("sewing tolerance must be positive");
  // Sewing two halves of a cap ruled between two curves, each parametrised
  // its own way, can widen their shared edge's tolerance past the body's
  // thickness, even once mended (planar_faces.cpp, sewn_edges.cpp). When an
  // edge is that wide, the sewing is done again with the flat faces whose
  // parametrisation collapses on their plane, where each face's curve is a
  // projection, and kept when it is tighter (a sewing with a result: the
  // first one's is empty only when it had no edge to widen).
  std::unique_ptr<BRepBuilderAPI_Sewing> sewing;
  TopTools_DataMapOfShapeShape on_plane;
  if (options.sew && info.free_curves_before_sewing > 0) {
    auto sewn = [&](const TopoDS_Shape& in, int& mended, double& widest) {
      auto s = std::make_unique<BRepBuilderAPI_Sewing>(cad->tolerance);
      s->Add(in);
      s->Perform();
      mended = 0;
      widest = 0;
      if (!s->SewedShape().IsNull()) {
        mended = mend_sewn_edges(s->SewedShape(), cad->tolerance);
        for (TopExp_Explorer e(s->SewedShape(), TopAbs_EDGE); e.More(); e.Next())
          widest = std::max(widest, BRep_Tool::Tolerance(TopoDS::Edge(e.Current())));
      }
      return s;
    };
    double widest = 0;
    sewing = sewn(shape, info.sewn_edges_mended, widest);
    if (widest > 100 * cad->tolerance) {
      int flat = 0, mended = 0;
      TopTools_DataMapOfShapeShape rebuilt_faces;
      const TopoDS_Shape flattened = flat_faces_before_sewing(shape, cad->tolerance, rebuilt_faces, flat);
      double widest_flat = 0;
      if (flat > 0) {
        auto on_planes = sewn(flattened, mended, widest_flat);
        if (widest_flat < widest && !on_planes->SewedShape().IsNull()) {
          sewing = std::move(on_planes);
          info.sewn_edges_mended = mended;
          info.flat_faces_before_sewing = flat;
          on_plane = rebuilt_faces;
        }
      }
    }
    if (!sewing->SewedShape().IsNull()) {
      shape = solids_from_closed_shells(sewing->SewedShape());
      info.sewn = true;
    }
  }
  auto rebuilt = [&](const TopoDS_Shape& s) { return on_plane.IsBound(s) ? on_plane(s) : s; };
  shape = remove_zero_area_faces(shape, diag, info.zero_area_faces_removed, cad->area);
  info.free_curves_after_sewing = count_free_curves(shape);
  bbox_diagonal(shape, info.bbox_min, info.bbox_max);
  for (const auto& [named, name] : names) {
    const TopoDS_Shape s = rebuilt(named);
    cad->names.emplace_back(sewing && sewing->IsModified(s) ? sewing->Modified(s) : s, name);
  }
  cad->shape = shape;
  cad->info = info;
  return CadFile(cad);
}

const ModelInfo& CadFile::info() const { return impl_->info; }

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

Model::Model(std::shared_ptr<Impl> impl) : impl_(std::move(impl)) {}
Model::~Model() = default;

const ModelInfo& Model::info() const { return impl_->info; }
std::string Model::face_name(int face) const { return impl_->face_names.at(face - 1); }
int Model::source_face(int face) const { return impl_->source_face.at(face - 1); }

void Model::record_mesh_union(int component, const std::string& failure) {
  Preparation& p = impl_->info.preparation;
  Component& c = p.components.at(component - 1);
  if (!failure.empty()) {
    c.route += "; at mesh level: " + failure;
    return;
  }
  const std::string was = "not united: ";
  if (c.route.compare(0, was.size(), was) == 0) c.brep_failure = c.route.substr(was.size());
  c.route = "mesh-level union";
  p.not_united.erase(std::remove(p.not_united.begin(), p.not_united.end(), component), p.not_united.end());
  ++p.united_at_mesh_level;
}
Boundary Model::boundary(int face) const {
  return impl_->boundary.empty() ? Boundary::Wall : impl_->boundary.at(face - 1);
}

int Model::fluid_side() const {
  if (!closed()) return 0;
  if (impl_->solids.Extent() == 1) {
    TopTools_IndexedMapOfShape shells;
    TopExp::MapShapes(impl_->solids(1), TopAbs_SHELL, shells);
    if (shells.Extent() > 1) return -1;
  }
  return 1;
}

std::vector<std::vector<int>> Model::solid_faces() const {
  std::vector<std::vector<int>> out;
  for (int s = 1; s <= impl_->solids.Extent(); ++s) {
    std::vector<int> ids;
    TopTools_IndexedMapOfShape fm;
    TopExp::MapShapes(impl_->solids(s), TopAbs_FACE, fm);
    for (int i = 1; i <= fm.Extent(); ++i) ids.push_back(impl_->faces.FindIndex(fm(i)));
    out.push_back(std::move(ids));
  }
  return out;
}

int Model::num_faces() const { return impl_->faces.Extent(); }
int Model::num_curves() const { return impl_->edges.Extent(); }
int Model::num_points() const { return impl_->vertices.Extent(); }

GeomAdaptor_Surface& Model::Impl::adaptor(int face) const {
  auto& mine = adaptors.local();
  if (mine.empty()) mine.resize(face_data.size());
  auto& a = mine[face - 1];
  if (!a) a = std::make_unique<GeomAdaptor_Surface>(face_data[face - 1].surface);
  return *a;
}

// uv shifted by whole wraps into the parameter range of a surface closed
// without a period (OcctFace::wrap); unchanged on other faces.
Vec2 Model::Impl::wrapped(int face, Vec2 uv) const {
  const OcctFace& d = face_data[face - 1];
  for (int axis = 0; axis < 2; ++axis) {
    const double w = d.wrap[axis];
    if (!(w > 0)) continue;
    const double from = uv[axis] - d.wrap_lo[axis];
    if (from < 0 || from > w) uv[axis] = d.wrap_lo[axis] + (from - std::floor(from / w) * w);
  }
  return uv;
}

SurfaceD1 Model::eval_face(int face, const Vec2& at) const {
  gp_Pnt p;
  gp_Vec du, dv;
  const Vec2 uv = impl_->wrapped(face, at);
  try {
    impl_->adaptor(face).D1(uv.x(), uv.y(), p, du, dv);
  } catch (const Standard_Failure& e) {
    throw EvaluationError("face " + std::to_string(face) + ": " + e.GetMessageString());
  }
  return {to_vec(p), to_vec(du), to_vec(dv)};
}

bool Model::principal_curvatures(int face, const Vec2& at, double& k1, double& k2) const {
  const auto& s = impl_->face_data[face - 1].surface;
  const Vec2 uv = impl_->wrapped(face, at);
  try {
    GeomLProp_SLProps props(s, uv.x(), uv.y(), 2, Precision::Confusion());
    if (!props.IsCurvatureDefined()) return false;
    k1 = props.MaxCurvature();
    k2 = props.MinCurvature();
    if (std::abs(k2) > std::abs(k1)) std::swap(k1, k2);
    return std::isfinite(k1) && std::isfinite(k2);
  } catch (const Standard_Failure&) {
    return false;
  }
}

bool Model::face_reversed(int face) const { return impl_->face_data[face - 1].reversed; }
UVBox Model::face_uv_bounds(int face) const { return impl_->face_data[face - 1].uv_bounds; }
double Model::face_period_u(int face) const { return impl_->face_data[face - 1].period_u; }
double Model::face_period_v(int face) const { return impl_->face_data[face - 1].period_v; }
double Model::face_wrap_u(int face) const {
  const OcctFace& d = impl_->face_data[face - 1];
  return d.period_u > 0 ? d.period_u : d.wrap.x();
}
double Model::face_wrap_v(int face) const {
  const OcctFace& d = impl_->face_data[face - 1];
  return d.period_v > 0 ? d.period_v : d.wrap.y();
}
double Model::face_area(int face) const { return impl_->face_data[face - 1].area; }
double Model::face_boundary_length(int face) const { return impl_->face_data[face - 1].boundary_length; }
std::vector<FaceLoop> Model::face_loops(int face) const { return impl_->face_data[face - 1].loops; }

// Newton iterations on |S(uv) - xyz|^2 from the given uv.
bool Model::project_to_face(int face, const Vec3& xyz, Vec2& uv) const {
  const UVBox box = face_uv_bounds(face);
  const Vec2 span = box.hi - box.lo;
  for (int it = 0; it < 30; ++it) {
    const SurfaceD1 s = eval_face(face, uv);
    const Vec3 r = xyz - s.p;
    Eigen::Matrix2d a;
    a << s.du.dot(s.du), s.du.dot(s.dv), s.du.dot(s.dv), s.dv.dot(s.dv);
    const Vec2 g(s.du.dot(r), s.dv.dot(r));
    const double det = a.determinant();
    if (!(std::abs(det) > 1e-300)) return false;
    Vec2 step = a.inverse() * g;
    // Keep a step within the face's parameter box scale to avoid jumping away.
    const double lim = 0.25 * span.norm();
    if (step.norm() > lim && lim > 0) step *= lim / step.norm();
    uv += step;
    if (step.norm() <= 1e-12 * (1 + span.norm())) return true;
  }
  return std::isfinite(uv.x()) && std::isfinite(uv.y());
}

// OCCT's extrema over the face's parameter box (a sampled search, then
// Newton from the best sample): the global nearest point.
bool Model::nearest_on_face(int face, const Vec3& xyz, Vec2& uv) const {
  const UVBox box = face_uv_bounds(face);
  try {
    GeomAPI_ProjectPointOnSurf extrema(gp_Pnt(xyz.x(), xyz.y(), xyz.z()), impl_->face_data[face - 1].surface,
                                       box.lo.x(), box.hi.x(), box.lo.y(), box.hi.y());
    if (extrema.NbPoints() == 0) return false;
    double u, v;
    extrema.LowerDistanceParameters(u, v);
    uv = Vec2(u, v);
    return true;
  } catch (const Standard_Failure&) {
    return false;
  }
}

void Model::curve_range(int curve, double& t0, double& t1) const {
  t0 = impl_->curve_data[curve - 1].t0;
  t1 = impl_->curve_data[curve - 1].t1;
}
bool Model::curve_degenerated(int curve) const { return impl_->curve_data[curve - 1].degenerated; }

Vec3 Model::eval_curve(int curve, double t) const {
  const auto& c = impl_->curve_data[curve - 1];
  if (c.curve.IsNull()) return point_xyz(c.start_point);
  try {
    return to_vec(c.curve->Value(t));
  } catch (const Standard_Failure& e) {
    throw EvaluationError("curve " + std::to_string(curve) + ": " + e.GetMessageString());
  }
}

Vec3 Model::curve_tangent(int curve, double t) const {
  const auto& c = impl_->curve_data[curve - 1];
  if (c.curve.IsNull()) return Vec3::Zero();
  gp_Pnt p;
  gp_Vec d;
  try {
    c.curve->D1(t, p, d);
  } catch (const Standard_Failure& e) {
    throw EvaluationError("curve " + std::to_string(curve) + ": " + e.GetMessageString());
  }
  return to_vec(d);
}

bool Model::curve_curvature(int curve, double t, double& k) const {
  const auto& c = impl_->curve_data[curve - 1];
  if (c.curve.IsNull()) return false;
  try {
    GeomLProp_CLProps props(c.curve, t, 2, Precision::Confusion());
    if (!props.IsTangentDefined()) return false;
    k = std::abs(props.Curvature());
    return std::isfinite(k);
  } catch (const Standard_Failure&) {
    return false;
  }
}

double Model::curve_length(int curve) const { return impl_->curve_data[curve - 1].length; }
int Model::curve_start_point(int curve) const { return impl_->curve_data[curve - 1].start_point; }
int Model::curve_end_point(int curve) const { return impl_->curve_data[curve - 1].end_point; }

Vec2 Model::eval_pcurve(int curve, int face, int side, double t) const {
  for (const auto& pc : impl_->curve_data[curve - 1].pcurves)
    if (pc.face == face && pc.side == side) {
      try {
        const gp_Pnt2d p = pc.curve->Value(t);
        return {p.X(), p.Y()};
      } catch (const Standard_Failure& e) {
        throw EvaluationError("curve " + std::to_string(curve) + " on face " + std::to_string(face) + ": " +
                              e.GetMessageString());
      }
    }
  throw EvaluationError("curve " + std::to_string(curve) + " has no parameter curve on face " + std::to_string(face));
}

Vec3 Model::point_xyz(int point) const {
  return to_vec(BRep_Tool::Pnt(TopoDS::Vertex(impl_->vertices(point))));
}

}  // namespace sizemesh
