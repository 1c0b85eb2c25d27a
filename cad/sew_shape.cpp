// A file's shape sewn (sew_shape): the CadFile the preparation starts from.
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <ShapeBuild_ReShape.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_DataMapOfShapeReal.hxx>
#include <TopTools_DataMapOfShapeShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "cad/occt_model.h"

namespace sizemesh {
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

// Exact areas of the faces in `faces`, computed in parallel (the costliest part of loading).
std::vector<double> face_areas(const TopTools_IndexedMapOfShape& faces) {
  std::vector<double> area(faces.Extent());
  tbb::parallel_for(0, faces.Extent(), [&](int i) { area[i] = face_area_exact(faces(i + 1)); });
  return area;
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

}  // namespace sizemesh
