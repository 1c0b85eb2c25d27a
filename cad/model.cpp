// Model: its accessors and the Geometry interface over the cached OpenCASCADE data.
#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomLProp_CLProps.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "cad/knot_lines.h"
#include "cad/occt_model.h"

namespace sizemesh {
namespace {

Vec3 to_vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
Vec3 to_vec(const gp_Vec& v) { return {v.X(), v.Y(), v.Z()}; }

}  // namespace

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
  auto& mine = per_thread.local().adaptors;
  if (mine.empty()) mine.resize(face_data.size());
  auto& a = mine[face - 1];
  if (!a) a = std::make_unique<GeomAdaptor_Surface>(face_data[face - 1].surface);
  return *a;
}

// A span's polynomial is (p+1)(q+1) times the size of one pole: the tables
// of every face together may take up to this much; faces past it, in id
// order, evaluate through the per-thread adaptor.
void Model::Impl::make_span_tables() {
  constexpr size_t kBudget = size_t(256) << 20;
  size_t used = 0;
  span_tables.clear();
  span_tables.resize(face_data.size());
  for (size_t f = 0; f < face_data.size(); ++f) {
    if (face_data[f].surface.IsNull() || used >= kBudget) continue;
    span_tables[f] = SpanTable::make(face_data[f].surface, kBudget - used);
    if (span_tables[f]) used += span_tables[f]->bytes();
  }
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
  ++impl_->per_thread.local().evaluations;
  try {
    const SpanTable* t = static_cast<size_t>(face - 1) < impl_->span_tables.size() ? impl_->span_tables[face - 1].get() : nullptr;
    if (!t || !t->d1(uv.x(), uv.y(), p, du, dv)) impl_->adaptor(face).D1(uv.x(), uv.y(), p, du, dv);
  } catch (const Standard_Failure& e) {
    throw EvaluationError("face " + std::to_string(face) + ": " + e.GetMessageString());
  }
  return {to_vec(p), to_vec(du), to_vec(dv)};
}

long long Model::surface_evaluations() const {
  long long n = 0;
  for (const auto& t : impl_->per_thread) n += t.evaluations;
  return n;
}

long long Model::thread_surface_evaluations() const { return impl_->per_thread.local().evaluations; }

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
bool Model::face_elementary(int face) const {
  switch (impl_->adaptor(face).GetType()) {
    case GeomAbs_Plane:
    case GeomAbs_Cylinder:
    case GeomAbs_Cone:
    case GeomAbs_Sphere:
    case GeomAbs_Torus: return true;
    default: return false;
  }
}
std::vector<double> Model::face_knots(int face, int direction) const {
  const GeomAdaptor_Surface& a = impl_->adaptor(face);
  if (a.GetType() != GeomAbs_BSplineSurface) return {};
  const Handle(Geom_BSplineSurface) s = a.BSpline();
  if (s.IsNull()) return {};
  const UVBox box = impl_->face_data[face - 1].uv_bounds;
  return detail::knots_inside(*s, direction == 0, box.lo[direction], box.hi[direction]);
}
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
