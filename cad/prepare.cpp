// Geometry preparation (prepare_shape): from the sewn shape's components to one wetted surface.
//
// Open components are repaired (cad/repair.cpp) and the closed ones united
// (cad/unite.cpp); open components left are imprinted on the bodies by the
// general fuse (cad/imprint.cpp). Every attempt runs within the union's time
// budget (cad/union_budget.cpp), and every result face records its source
// face.
#include "cad/prepare.h"
#include "core/stopwatch.h"

#include <BRepCheck_Analyzer.hxx>
#include <BRep_Builder.hxx>
#include <Message_ProgressRange.hxx>
#include <ShapeFix_Solid.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shell.hxx>
#include <gp_Pln.hxx>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "cad/actuator_disks.h"
#include "cad/coincident_faces.h"
#include "cad/components.h"
#include "cad/deadline.h"
#include "cad/face_list.h"
#include "cad/imprint.h"
#include "cad/inside_solids.h"
#include "cad/occt_model.h"
#include "cad/repair.h"
#include "cad/small_loops.h"
#include "cad/union_budget.h"

namespace sizemesh {
using namespace detail;  // the preparation's steps
namespace {

// Folds are split where the surface turns over within this share of the
// model's diagonal: half the default smallest element (sizing/params.h).
constexpr double kFoldBand = 5e-4;

double diagonal_of(const Component& c) { return (c.bbox_max - c.bbox_min).norm(); }

}  // namespace

PreparedShape prepare_shape(const TopoDS_Shape& sewn, const TopTools_IndexedMapOfShape& original,
                            const TopTools_DataMapOfShapeReal& area, double tol, double diagonal,
                            const LoadOptions& options, Preparation& info) {
  const bool unite = options.unite && options.sew;
  PreparedShape out;
  info = Preparation{};
  info.union_requested = unite;
  info.faces_before = original.Extent();
  for (int i = 1; i <= original.Extent(); ++i) out.source.Bind(original(i), i);
  const std::vector<TopoDS_Shape> parts = components_of(sewn);
  info.seconds_budget = default_budget(options, parts.size());
  WorkBudget deadline(info.seconds_budget);
  for (const auto& s : parts) {
    info.components.push_back(describe(s, area));
    for (const auto& f : faces_of(s)) info.components.back().face_ids.push_back(original.FindIndex(f));
  }
  if (!unite) {
    for (auto& c : info.components) c.role = c.closed ? "solid" : "sheet";
    out.shape = sewn;
    info.faces_after = info.faces_before;
    return out;
  }

  Vec3 lo = info.components.front().bbox_min, hi = info.components.front().bbox_max;
  for (const Component& c : info.components) lo = lo.cwiseMin(c.bbox_min), hi = hi.cwiseMax(c.bbox_max);
  const HalfModelPlanes half = half_model_planes(lo, hi, tol);
  // Repair each open component; collect the solids and sheets.
  std::vector<TopoDS_Shape> solids, sheets;
  std::vector<TopoDS_Shape> invalid;  // solids no mending makes valid: for the union of meshes
  std::vector<int> solid_component, sheet_component;
  FaceList loose;
  std::vector<int> loose_component;
  std::vector<std::pair<int, gp_Pln>> flat;  // components that are flat open disks, their plane
  const Follow follow = [&](const TopoDS_Face& from, const TopoDS_Face& to) {
    if (out.source.IsBound(from) && !out.source.IsBound(to)) out.source.Bind(to, out.source(from));
  };
  Stopwatch step;
  // Bodies that meet face to face are repaired as one: the first holds the
  // faces of both, the second is a part of it.
  std::vector<TopoDS_Shape> joined_parts = parts;
  const std::vector<std::pair<int, int>> joins = face_to_face(parts, tol);
  for (const auto& [a, b] : joins) {
    joined_parts[a] = compound_of(joined(faces_of(parts[a]), faces_of(parts[b])));
    joined_parts[b] = TopoDS_Shape();
    auto& ids = info.components[a].face_ids;
    ids.insert(ids.end(), info.components[b].face_ids.begin(), info.components[b].face_ids.end());
  }
  for (size_t k = 0; k < parts.size(); ++k) {
    Component& c = info.components[k];
    const TopoDS_Shape& s = joined_parts[k];
    if (s.IsNull()) continue;  // joined to another body (joins)
    // A body closed with faces back to back inside it (two halves sewn
    // together with both root caps) bounds no volume the fuse can use: it
    // goes through the repair, which takes such pairs out.
    const bool back_to_back = (s.ShapeType() == TopAbs_SOLID || c.closed) && !coincident_pairs(faces_of(s), tol).empty();
    if (s.ShapeType() == TopAbs_SOLID && !back_to_back) {
      c.role = "solid";
      // A solid as read may be invalid (a face turned inside out in its
      // shell): the general fuse would then classify it wrongly and drop
      // what lies outside. Mended first (ShapeFix_Solid orients its shells'
      // faces); a solid it cannot mend goes to the union of meshes.
      TopoDS_Shape solid = s;
      if (!BRepCheck_Analyzer(solid).IsValid()) {
        ShapeFix_Solid fix(TopoDS::Solid(solid));
        fix.Perform();
        const TopoDS_Shape mended = fix.Solid();
        if (!mended.IsNull() && mended.ShapeType() == TopAbs_SOLID && BRepCheck_Analyzer(mended).IsValid()) {
          solid = mended;  // its faces the same, some turned: their sources hold
        } else {
          c.route = "not united: its solid is not valid";
          info.not_united.push_back(static_cast<int>(k) + 1);
          invalid.push_back(s);
          continue;
        }
      }
      solids.push_back(solid);
      solid_component.push_back(static_cast<int>(k));
      continue;
    }
    Repair r;
    if (c.closed && !back_to_back) {
      r.closed = s;
    } else if (s.ShapeType() == TopAbs_FACE && count_free_curves(s) == 0) {
      // One face closed on itself (a body of revolution with poles): its shell.
      TopoDS_Shell shell;
      BRep_Builder b;
      b.MakeShell(shell);
      b.Add(shell, s);
      shell.Closed(true);
      r.closed = shell;
    } else if (s.ShapeType() == TopAbs_SHELL || s.ShapeType() == TopAbs_FACE || back_to_back) {
      // An open shell, or one open face (OpenVSP writes a whole wing or fin
      // as one face, its caps folded onto the chord): sewn pieces go through
      // the repair.
      // Caps built into a skin (OpenVSP's root and tip caps, flat strips
      // folded onto the chord) split off as faces of their own, when that
      // finds caps back to back: two halves' root caps, a pod's tip cap and
      // its strut's root cap. The repair then takes both of each pair out.
      FaceList faces = faces_of(s);
      int folds = 0;
      const TopoDS_Shape split = split_folds(s, kFoldBand * diagonal, follow, folds, true);
      if (folds > 0 && coincident_pairs(faces_of(split), tol).size() > coincident_pairs(faces, tol).size()) {
        faces = faces_of(split);
        info.faces_split_at_folds += folds;
      }
      r = repair_component(faces, tol, diagonal_of(c), half, options.domain.symmetry_axis);
      deadline.add(r.helper_work);
      for (const auto& [f, piece] : r.split) follow(f, piece);
      for (const auto& f : r.kept) follow(f, r.sewn.after(f));
    }
    if (!r.half_open.IsNull()) {
      c.role = "sheet";
      c.route = std::string("half model: open on the plane ") + static_cast<char>('x' + r.half_model_axis) + " = 0";
      c.faces_removed = r.duplicates + r.internal + static_cast<int>(r.sheets.size());
      info.duplicate_faces_removed += r.duplicates;
      info.internal_faces_removed += r.internal;
      info.half_model_axis = r.half_model_axis;
      sheets.push_back(r.half_open);
      sheet_component.push_back(static_cast<int>(k));
      for (const auto& f : r.sheets) loose.push_back(f), loose_component.push_back(static_cast<int>(k));
      continue;
    }
    const std::vector<TopoDS_Shape> closed = r.closed.IsNull() ? std::vector<TopoDS_Shape>() : solids_of(r.closed);
    if (closed.empty()) {
      c.role = "sheet";
      if (gp_Pln plane; flat_disk(s, tol, plane)) flat.emplace_back(static_cast<int>(k), plane);
      sheets.push_back(s);
      sheet_component.push_back(static_cast<int>(k));
      continue;
    }
    c.role = "solid";
    c.faces_removed = r.duplicates + r.internal + static_cast<int>(r.sheets.size());
    c.caps_added = r.caps;
    info.caps_added += r.caps;
    info.duplicate_faces_removed += r.duplicates;
    info.internal_faces_removed += r.internal;
    if (!c.closed || back_to_back) ++info.components_repaired;
    for (const auto& solid : closed) solids.push_back(solid), solid_component.push_back(static_cast<int>(k));
    for (const auto& f : r.sheets) loose.push_back(f), loose_component.push_back(static_cast<int>(k));
  }
  // Flat disks a body passes through (actuator disks) are left out.
  std::vector<TopoDS_Shape> bodies = solids;
  bodies.insert(bodies.end(), invalid.begin(), invalid.end());
  for (const auto& [k, plane] : flat)
    if (pierced(parts[k], plane, bodies, tol)) {
      const auto at = std::find(sheet_component.begin(), sheet_component.end(), k) - sheet_component.begin();
      sheets.erase(sheets.begin() + at);
      sheet_component.erase(sheet_component.begin() + at);
      info.components[k].role = "disk";
      info.components[k].route = "left out: a flat disk a body passes through, no wall";
      info.left_out.push_back(k + 1);
    }
  // A sheet wholly inside a body or on its surface (a wing's planform plane
  // exported as a component of its own, between the skins) bounds no fluid:
  // it is left out. Every one of 9 points spread over each face must be in:
  // a fin reaching out of a body keeps its outer part as a wall.
  const Solids inside(solids, tol);
  for (size_t i = 0; i < sheets.size();) {
    const FaceList faces = faces_of(sheets[i]);
    const bool held = !solids.empty() && !faces.empty() && std::all_of(faces.begin(), faces.end(), [&](const TopoDS_Face& f) {
                        return inside.hold_whole(f, 9);
                      });
    if (!held) {
      ++i;
      continue;
    }
    const int k = sheet_component[i];
    sheets.erase(sheets.begin() + static_cast<long>(i));
    sheet_component.erase(sheet_component.begin() + static_cast<long>(i));
    info.components[k].role = "internal";
    info.components[k].route = "left out: a sheet inside a body";
    info.internal_sheets.push_back(k + 1);
  }
  // Faces taken out of one component may lie inside another one (the plane
  // of the left tail inside the right tail): those are internal too.
  for (size_t i = 0; i < loose.size(); ++i) {
    if (inside.hold(loose[i])) ++info.internal_faces_removed;
    else sheets.push_back(loose[i]), sheet_component.push_back(loose_component[i]);
  }
  info.repair_seconds = step.lap();

  // Components the options send straight to the mesh-level union.
  std::vector<TopoDS_Shape> apart = invalid;
  for (int k : options.mesh_union)
    if (k < 1 || k > static_cast<int>(info.components.size()))
      throw Error("--mesh-union " + std::to_string(k) + ": the model has " + std::to_string(info.components.size()) +
                  " components (sizemesh --info lists them)");
  if (!options.describe_only) {
    std::vector<TopoDS_Shape> kept;
    std::vector<int> kept_component;
    for (size_t i = 0; i < solids.size(); ++i) {
      const int k = solid_component[i];
      if (options.mesh_union_all || std::count(options.mesh_union.begin(), options.mesh_union.end(), k + 1)) {
        info.components[k].route = "not united: --mesh-union asks for a union of meshes";
        info.not_united.push_back(k + 1);
        apart.push_back(solids[i]);
      } else {
        kept.push_back(solids[i]), kept_component.push_back(k);
      }
    }
    solids.swap(kept);
    solid_component.swap(kept_component);
  }
  if (options.describe_only) {
    info.union_skipped = true;
  } else if (solids.size() >= 2) {
    const TopoDS_Shape united =
        unite_solids(solids, solid_component, tol, deadline, meshes_take_over(options), follow, options.progress, info);
    solids.clear();
    for (TopExp_Explorer ex(united, TopAbs_SOLID); ex.More(); ex.Next()) solids.push_back(ex.Current());
  } else if (solids.size() == 1) {
    info.components[solid_component[0]].route = "alone: the only closed component";
  }
  info.union_seconds = step.lap();
  solids.insert(solids.end(), apart.begin(), apart.end());
  TopoDS_Shape result;
  if (!options.describe_only && !sheets.empty() && solids.size() + sheets.size() >= 2) {
    if (options.progress) options.progress("imprinting " + std::to_string(sheets.size()) + " open components");
    result = imprint_sheets(solids, sheets, tol, deadline, follow, info);
    for (int k : sheet_component) {
      if (info.components[k].role == "sheet")
        info.components[k].route = result.IsNull() ? "not united: " + info.fallback : "imprinted";
      if (result.IsNull()) info.not_united.push_back(k + 1);
    }
  }
  if (result.IsNull()) {
    BRep_Builder b;
    TopoDS_Compound all;
    b.MakeCompound(all);
    for (const auto& s : sheets) b.Add(all, s);
    for (const auto& s : solids) b.Add(all, s);
    result = all;
  }
  for (const auto& [a, b] : joins) {
    Component& c = info.components[b];
    c.role = info.components[a].role;
    const std::string& with = info.components[a].route;
    c.route = "one body with component " + std::to_string(a + 1) + " (faces back to back)" + (with.empty() ? "" : ": " + with);
  }
  info.imprint_seconds = step.lap();
  std::sort(info.not_united.begin(), info.not_united.end());
  info.not_united.erase(std::unique(info.not_united.begin(), info.not_united.end()), info.not_united.end());
  // --info stops here: the last splits serve the mesher, and a description
  // of the file has no use for them.
  if (options.describe_only) {
    out.shape = result;
    info.faces_after = static_cast<int>(faces_of(out.shape).size());
    return out;
  }
  // Folds narrower than half the default smallest element become curves.
  int folds = 0;
  out.shape = split_folds(result, kFoldBand * diagonal, follow, folds);
  // Strips too narrow for sewing to keep their corners (some split off at a
  // fold just now) become curves.
  out.shape = collapse_strips(out.shape, 2 * tol, follow, info.strip_faces_collapsed);
  info.faces_split_at_folds += folds;
  // Flat faces on their plane: no region of zero area in their uv.
  out.shape = planar_faces(out.shape, tol, out.source, follow, info.faces_made_planar);
  out.shape = drop_small_loops(out.shape, tol, follow, info.small_loops_dropped);
  info.faces_after = static_cast<int>(faces_of(out.shape).size());
  info.finish_seconds = step.lap();
  return out;
}

}  // namespace sizemesh
