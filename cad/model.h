// A loaded CAD model: the B-rep with stable ids, its unit and sewing report.
// OpenCASCADE stays behind the pimpl; sizing/ and mesher/ use it as a Geometry.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "cad/prepare.h"

namespace sizemesh {

// The outer boundary of the flow domain around the body, and the symmetry
// plane of a half model (cad/flow_domain.cpp).
struct FlowDomainOptions {
  enum class FarField { None, Sphere, Box };
  FarField farfield = FarField::None;
  double size = 0;          // sphere radius or half the box side; 0: 20 body diagonals
  double element_size = 0;  // element size on the far field; 0: a tenth of `size`
  int symmetry_axis = -1;   // -1 none, 0 x, 1 y, 2 z: keep the body on one side of that plane
  double symmetry_at = 0;   // the plane's coordinate ...
  bool symmetry_at_given = false;  // ... when given; else 0, or the body's nearest side to 0
  bool active() const { return farfield != FarField::None || symmetry_axis >= 0; }
};

// Called with one line as each long step of loading starts.
using ProgressSink = std::function<void(const std::string&)>;

struct LoadOptions {
  bool sew = true;                  // sew faces that touch so they share curves
  double sewing_tolerance_rel = 1e-5;  // sewing tolerance / bounding-box diagonal
  bool unite = true;                // repair components and fuse the closed ones (cad/prepare.h)
  FlowDomainOptions domain;
  double union_seconds = 0;         // the union's work budget (CPU seconds, cad/deadline.h); 0: union_budget's default
  ProgressSink progress;            // told which component is being united
  bool describe_only = false;       // repair but no union (what --info needs to describe the file)
  // Components (1-based, as --info numbers them) united as meshes without a
  // B-rep union tried (mesher/mesh_union.h); all of them when mesh_union_all.
  std::vector<int> mesh_union;
  bool mesh_union_all = false;
};

// What the flow-domain step built (all zero when none was asked for).
struct FlowDomain {
  std::string farfield;        // "sphere", "box" or empty
  Vec3 center = Vec3::Zero();
  double size = 0, element_size = 0;
  int symmetry_axis = -1;
  double symmetry_at = 0;
  int farfield_faces = 0, symmetry_faces = 0;
  std::vector<Vec3> inside_points;  // one inside each closed body the far field surrounds (volume meshers' holes)
};

struct ModelInfo {
  std::string path;
  std::string format;      // STEP, IGES or BREP
  std::string unit;        // length unit of the file, e.g. "mm"
  Vec3 bbox_min, bbox_max;
  int solids = 0, shells = 0, faces = 0, curves = 0, points = 0;
  int faces_before_sewing = 0;   // sewing drops faces degenerate at its tolerance
  int zero_area_faces_removed = 0;  // collapsed faces that cannot carry a mesh
  int flat_faces_before_sewing = 0;  // flat faces put on their plane before sewing (cad/planar_faces.cpp)
  int degenerate_edges_made_real = 0;  // before sewing (real_degenerate_edges, cad/pinch_split.cpp)
  int sewn_edges_mended = 0;         // sewn edges whose tolerance had grown, their curves projected afresh
  int free_curves_before_sewing = 0;
  int free_curves_after_sewing = 0;
  bool sewn = false;       // sewing was run
  int entities_failed = 0;     // file entities the reader could not read or translate
  std::string first_failure;   // the first of them: "entity #26 (AXIS2_PLACEMENT_3D): <reason>"
  std::vector<std::string> read_repairs;  // what the reader mended in the file's layout, one line each
  int sewn_faces = 0;          // faces after sewing: the ids the config file and --no-union use
  Preparation preparation;     // components, repair and union
  FlowDomain domain;           // far field and symmetry plane; the bounding box is the body's
  double diagonal() const { return (bbox_max - bbox_min).norm(); }
};

class Model : public Geometry {
 public:
  struct Impl;  // OpenCASCADE data, cad/occt_model.h

  explicit Model(std::shared_ptr<Impl> impl);
  ~Model() override;

  const ModelInfo& info() const;
  const Impl& impl() const { return *impl_; }
  // Name from the file (STEP entity name) or empty.
  std::string face_name(int face) const;
  // The sewn model's face (1..info().sewn_faces) this face came from; the
  // face itself when no union ran; 0 when unknown.
  int source_face(int face) const;
  // What the face bounds: the body, the far field or the symmetry plane.
  Boundary boundary(int face) const;
  // Records how the mesh-level union ended for a component (1-based) the
  // B-rep union left out: united when `failure` is empty, else why not.
  void record_mesh_union(int component, const std::string& failure);
  // Faces (ids) of each solid; empty when the model has no solids.
  std::vector<std::vector<int>> solid_faces() const;
  // True when every non-degenerate curve bounds exactly two face sides.
  bool closed() const override { return info().free_curves_after_sewing == 0; }
  // A closed model that is one solid with cavities (several shells) is taken
  // for a flow domain: the fluid is inside it. Other closed models are bodies.
  int fluid_side() const override;

  int num_faces() const override;
  int num_curves() const override;
  int num_points() const override;
  SurfaceD1 eval_face(int face, const Vec2& uv) const override;
  long long surface_evaluations() const override;
  long long thread_surface_evaluations() const override;
  bool principal_curvatures(int face, const Vec2& uv, double& k1, double& k2) const override;
  bool face_reversed(int face) const override;
  bool face_elementary(int face) const override;
  std::vector<double> face_knots(int face, int direction) const override;
  UVBox face_uv_bounds(int face) const override;
  double face_period_u(int face) const override;
  double face_period_v(int face) const override;
  double face_wrap_u(int face) const override;
  double face_wrap_v(int face) const override;
  double face_area(int face) const override;
  double face_boundary_length(int face) const override;
  std::vector<FaceLoop> face_loops(int face) const override;
  bool project_to_face(int face, const Vec3& xyz, Vec2& uv) const override;
  bool nearest_on_face(int face, const Vec3& xyz, Vec2& uv) const override;
  void curve_range(int curve, double& t0, double& t1) const override;
  bool curve_degenerated(int curve) const override;
  Vec3 eval_curve(int curve, double t) const override;
  Vec3 curve_tangent(int curve, double t) const override;
  bool curve_curvature(int curve, double t, double& k) const override;
  double curve_length(int curve) const override;
  int curve_start_point(int curve) const override;
  int curve_end_point(int curve) const override;
  Vec2 eval_pcurve(int curve, int face, int side, double t) const override;
  Vec3 point_xyz(int point) const override;

 private:
  std::shared_ptr<Impl> impl_;
};

// A file's shape, sewn, before preparation (OpenCASCADE data behind Impl).
class CadFile {
 public:
  struct Impl;  // cad/occt_model.h
  explicit CadFile(std::shared_ptr<Impl> impl) : impl_(std::move(impl)) {}
  const ModelInfo& info() const;
  const Impl& impl() const { return *impl_; }

 private:
  std::shared_ptr<Impl> impl_;
};

// Reads STEP (.stp/.step), IGES (.igs/.iges) or OpenCASCADE BREP (.brep),
// chosen by content first and extension second, and sews it. Throws Error
// with one sentence.
CadFile read_cad(const std::string& path, const LoadOptions& options = {});

// Geometry preparation (cad/prepare.h), then stable ids and cached
// per-entity data.
Model prepare_model(const CadFile& cad, const LoadOptions& options = {});

// The union's work budget (CPU seconds, cad/deadline.h) for a file: options.union_seconds, or by
// default 1.5 s per component after sewing, 4 to 8 s (the union of meshes
// takes what it leaves); inside a flow domain 4 s per component, at least
// 12 s. An attempt past it is abandoned for the next route.
double union_budget(const CadFile& cad, const LoadOptions& options);

// read_cad then prepare_model.
Model load_model(const std::string& path, const LoadOptions& options = {});

}  // namespace sizemesh
