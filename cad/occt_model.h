// OpenCASCADE side of Model; included only by cad/*.cpp and tests that build shapes.
#pragma once

#include <BOPAlgo_Builder.hxx>
#include <Geom2d_Curve.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>
#include <TopTools_DataMapOfShapeInteger.hxx>
#include <TopTools_DataMapOfShapeReal.hxx>
#include <TopTools_DataMapOfShapeShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <functional>
#include <memory>
#include <tbb/enumerable_thread_specific.h>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>

#include "cad/model.h"
#include "cad/span_table.h"

namespace sizemesh {

// Per-face data cached at load time (thread-safe to evaluate: Geom objects only).
struct OcctFace {
  Handle(Geom_Surface) surface;  // with the face's location applied
  bool reversed = false;
  UVBox uv_bounds;
  double period_u = 0, period_v = 0;
  // A surface closed in u or v without a period, met across a seam edge:
  // its parameter range there (wrap) from `wrap_lo` (Geometry::face_wrap_u).
  Vec2 wrap = Vec2::Zero(), wrap_lo = Vec2::Zero();
  double area = 0, boundary_length = 0;
  std::vector<FaceLoop> loops;
};

struct OcctPCurve {
  int face = 0, side = 0;
  Handle(Geom2d_Curve) curve;
};

struct OcctCurve {
  Handle(Geom_Curve) curve;  // null for degenerated edges
  double t0 = 0, t1 = 0;
  bool degenerated = false;
  double length = 0;
  int start_point = 0, end_point = 0;
  std::vector<OcctPCurve> pcurves;
};

struct Model::Impl {
  TopoDS_Shape shape;
  TopTools_IndexedMapOfShape faces, edges, vertices, solids, shells;
  ModelInfo info;
  std::vector<std::string> face_names;
  std::vector<OcctFace> face_data;    // index id - 1
  std::vector<OcctCurve> curve_data;  // index id - 1
  std::vector<int> source_face;       // index id - 1: the sewn model's face it came from
  std::vector<Boundary> boundary;     // index id - 1: what the face bounds (Wall when empty)
  // Per thread, each face's surface behind an adaptor that caches the
  // polynomial of the B-spline span it last evaluated (BSplSLib_Cache): the
  // mesher's evaluations come in runs within a span, and a cached span
  // evaluates several times faster than locating it and running de Boor anew.
  // An adaptor is not thread-safe, so each thread has its own, made on first use.
  struct PerThread {
    std::vector<std::unique_ptr<GeomAdaptor_Surface>> adaptors;
    long long evaluations = 0;  // eval_face calls on this thread
  };
  mutable tbb::enumerable_thread_specific<PerThread> per_thread;
  // Per face, its B-spline spans' polynomials, shared by the threads
  // (cad/span_table.h); null for other surfaces and past the model's budget.
  std::vector<std::unique_ptr<SpanTable>> span_tables;
  void make_span_tables();
  GeomAdaptor_Surface& adaptor(int face) const;
  Vec2 wrapped(int face, Vec2 uv) const;
};

// A file's shape after sewing, before preparation: what read_cad returns.
struct CadFile::Impl {
  TopoDS_Shape shape;
  ModelInfo info;
  double tolerance = 0;  // sewing tolerance, model units
  TopTools_DataMapOfShapeReal area;  // exact face areas known from sewing
  std::vector<std::pair<TopoDS_Shape, std::string>> names;  // sewn faces and their names in the file
};

// Sews (when asked and needed) and drops faces of zero area. `info` carries
// what the reader knew (path, format, unit); `names` maps shapes as read to
// their names in the file.
CadFile sew_shape(const TopoDS_Shape& shape, ModelInfo info, const LoadOptions& options,
                  const std::vector<std::pair<TopoDS_Shape, std::string>>& names = {});

// Curves bounding exactly one face side (seams and degenerate curves excluded).
int count_free_curves(const TopoDS_Shape& shape);

// Whether a preparation step that turned `before` into `after` may be kept:
// a closed shape stays closed, and the faces `after` has and `before` has
// not (those the step made or changed: its pieces, and neighbours whose
// edges it split) pass BRepCheck. A step changes no other face, and checking
// every face again costs the wire self-intersection test of every B-spline
// pcurve of the model.
bool step_keeps_shape_valid(const TopoDS_Shape& before, const TopoDS_Shape& after);

// The solid a closed shell bounds, oriented outward; null when it cannot be made.
TopoDS_Solid solid_from_shell(const TopoDS_Shell& shell);

// Called with a piece of a face for every face a step of the preparation
// replaces (face before, face after), so each result face keeps its source id.
using Follow = std::function<void(const TopoDS_Face&, const TopoDS_Face&)>;

// cad/imprint.cpp: the faces a general fuse made of face f (f itself when
// it kept it whole).
std::vector<TopoDS_Face> pieces_of(BOPAlgo_Builder& fuse, const TopoDS_Face& f);

// One general fuse: the result, each input face's pieces in it (face before,
// face after), and why it failed (empty when it did not).
struct FuseStep {
  TopoDS_Shape shape;
  std::vector<std::pair<TopoDS_Face, TopoDS_Face>> pieces;
  std::string failure;
  std::string out_of_time;  // when it was stopped for time, how ("did not end within 12.0 s"); else empty
  int pocket_faces = 0;     // faces of enclosed air pockets dropped
  double worked = 0;  // CPU seconds of the child's thread that ran it (0 when it ran on this one, whose clock has it)
};

// cad/isolated_fuse.cpp: `here(parallel)` (a fuse of `parts`, budgeted
// `seconds` of work) run in a child process that is ended at kWallPerWork
// times `seconds` of wall time whether or not the fuse listens,
// its result handed back exactly (BinTools); parallel when the child may
// start threads (run_in_child), else on one thread. `here(true)` in this
// process when no child can be made.
FuseStep fuse_in_child(const std::vector<TopoDS_Shape>& parts, double seconds,
                       const std::function<FuseStep(bool parallel)>& here);

class WorkBudget;
// cad/unite.cpp: the union of closed `solids` (each of info.components
// [component[i]]) all at once, or else one at a time, grouped by
// overlapping boxes, each step checked and retried (fuzzy, healed) within
// `deadline`, a budget of work (cad/deadline.h; each fuse's adds to it); when `meshes_take_over` (the union of meshes unites what is
// left) and the union of all at once ran out of its time, none is tried one
// at a time: such a fuse takes seconds a pair. Returns a compound
// of the united groups and of the solids left out; sets each component's
// route, info.not_united, info.solids_fused and info.fused.
TopoDS_Shape unite_solids(const std::vector<TopoDS_Shape>& solids, const std::vector<int>& component, double tol,
                          WorkBudget& deadline, bool meshes_take_over, const Follow& follow,
                          const ProgressSink& progress, Preparation& info);

// The coordinate planes through 0 that bound the model's box (within
// `tolerance`): where the root of a half model lies.
struct HalfModelPlanes {
  bool candidate[3] = {false, false, false};
  double tolerance = 0;
};
HalfModelPlanes half_model_planes(const Vec3& lo, const Vec3& hi, double tol);

// cad/caps.cpp: planar faces over the closed, flat loops of free curves
// of `shape`. Loops on a half-model plane are capped only when its axis is
// `cap_axis` (the symmetry plane the run cuts at; -1 none), else counted.
struct Caps {
  std::vector<TopoDS_Face> faces;
  int half_model_loops = 0;
  int half_model_axis = -1;
};
Caps planar_caps(const TopoDS_Shape& shape, double tol, const HalfModelPlanes& half, int cap_axis);

// cad/pinch_split.cpp: `faces` with each face whose boundary runs along
// one line twice (two coincident edges: a wing's zero-thickness tip) split in
// two between them, so sewing can join the halves; (face, piece) pairs in
// `pieces`.
std::vector<TopoDS_Face> split_pinched(const std::vector<TopoDS_Face>& faces, double tol,
                                       std::vector<std::pair<TopoDS_Face, TopoDS_Face>>& pieces, int depth = 0);
// A degenerated edge is a point of its face's surface; one whose pcurve the
// surface maps onto a curve longer than 100 tol (an OpenVSP fuselage whose
// end section is a vertical line, flagged as a point) becomes a real edge
// on that curve, closed at its vertex, which split_pinched() then opens at
// its folds. `made`: how many.
TopoDS_Shape real_degenerate_edges(const TopoDS_Shape& shape, double tol, int& made);

// The prepared shape and, for each of its faces, the id of the sewn face it
// came from (ids: `original`'s indices).
struct PreparedShape {
  TopoDS_Shape shape;
  TopTools_DataMapOfShapeInteger source;
};
// cad/prepare.cpp: components, repair and (when `unite`) union.
// `area`: exact areas of the sewn faces; `diagonal`: the model's bounding-box
// diagonal.
// `options.unite && options.sew` asks for repair and union, within
// options.union_seconds.
PreparedShape prepare_shape(const TopoDS_Shape& sewn, const TopTools_IndexedMapOfShape& original,
                            const TopTools_DataMapOfShapeReal& area, double tolerance, double diagonal,
                            const LoadOptions& options, Preparation& info);

// cad/fold_split.cpp: faces of `shape` split along their C0 knot lines
// where the surface turns over (normals more than 60 degrees apart) within
// `band` on either side, so that the fold becomes a curve the mesh follows,
// or where the parametric speed across the line jumps more than threefold
// (a front in uv folds triangles that straddle such a line).
// `follow(face, piece)` is called for every face replaced; `split` counts
// the faces cut. Returns `shape` itself when nothing is split or the result
// would be invalid, or open where `shape` was closed. With `loose`, the
// faces are divided each on its own, pieces healed where the division left
// them invalid, and the result is a compound of faces to be sewn again.
TopoDS_Shape split_folds(const TopoDS_Shape& shape, double band,
                         const std::function<void(const TopoDS_Face&, const TopoDS_Face&)>& follow, int& split,
                         bool loose = false);

// cad/strip_faces.cpp: faces of `shape` that are strips between two
// long curves narrower than `width` everywhere removed, their two long curves
// made one shared by the faces either side; `follow(face, result)` for each
// face beside a strip, `collapsed` counts the strips. Returns `shape` itself
// when there is none, or when a face beside one would be invalid or a curve
// left free.
TopoDS_Shape collapse_strips(const TopoDS_Shape& shape, double width,
                             const std::function<void(const TopoDS_Face&, const TopoDS_Face&)>& follow,
                             int& collapsed);

// cad/planar_faces.cpp: faces of `shape` whose surface (a B-spline or
// other) lies on a plane within `tol` and whose parametrisation collapses
// (inside or along a side) rebuilt on that plane with the same edges, less
// those of zero length, and neighbouring ones cut from one face (`source`) on one plane
// merged; `follow(face, result)` for each, `rebuilt` counts the faces
// rebuilt. Returns `shape` itself when none is, or when the result would be
// invalid.
TopoDS_Shape planar_faces(const TopoDS_Shape& shape, double tol, const TopTools_DataMapOfShapeInteger& source,
                          const Follow& follow, int& rebuilt);

// cad/sewn_edges.cpp: edges of a sewn `shape` whose tolerance grew past 100
// times the sewing's `tol`, between two planes or between planes and one
// curved face, get their curves on the planes projected afresh from the
// edge's 3D curve (rebuilt first from the curved face's curve, when there is
// one), and tolerances made the least that holds (the shape is changed in
// place). Returns how many became tighter.
int mend_sewn_edges(const TopoDS_Shape& shape, double tol);

// The same rebuild on a copy of faces not yet sewn, each face checked alone;
// `shape` is left as it is. `image` gets each face and solid of `shape` with
// its counterpart in the result; `rebuilt` counts the faces put on a plane.
TopoDS_Shape flat_faces_before_sewing(const TopoDS_Shape& shape, double tol, TopTools_DataMapOfShapeShape& image,
                                      int& rebuilt);

// cad/flow_domain.cpp: the far field and the symmetry plane around the
// prepared `body` (bounding box lo..hi, model tolerance `tol`). `source` is
// updated for the body's faces the cut splits; `kind` gets Boundary::Farfield
// or Boundary::Symmetry (as int) for the faces that bound the domain. Throws
// Error when the far field is too small or the body cannot be cut.
TopoDS_Shape add_flow_domain(const TopoDS_Shape& body, TopTools_DataMapOfShapeInteger& source,
                             const FlowDomainOptions& o, const Vec3& lo, const Vec3& hi, double tol,
                             FlowDomain& info, TopTools_DataMapOfShapeInteger& kind);

// The bounding box of a shape; throws Error when it is empty or unusable.
double bbox_diagonal(const TopoDS_Shape& shape, Vec3& lo, Vec3& hi);

// Area by OCCT's fixed-order rule, or (relative_eps > 0) adaptively to that
// relative accuracy: for faces the preparation made (union pieces, faces split
// or with split edges), where the fixed rule can be off by a few percent.
double face_area_exact(const TopoDS_Shape& face, double relative_eps = 0);

// sew_shape then prepare_model.
Model model_from_shape(const TopoDS_Shape& shape, ModelInfo info, const LoadOptions& options,
                       const std::vector<std::pair<TopoDS_Shape, std::string>>& names = {});

// For shapes built in code (tests, examples): unit "unknown", format "shape".
Model model_from_shape(const TopoDS_Shape& shape, const LoadOptions& options = {});

}  // namespace sizemesh
