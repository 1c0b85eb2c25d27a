// The general fuse of bodies and open components (imprint_sheets), and a face's pieces after a fuse (pieces_of).
#include "cad/imprint.h"

#include <BOPAlgo_Alerts.hxx>
#include <BOPAlgo_Builder.hxx>
#include <BRep_Builder.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_MapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>

#include "cad/deadline.h"
#include "cad/face_list.h"
#include "cad/inside_solids.h"

namespace sizemesh {
namespace detail {

TopoDS_Shape imprint_sheets(const std::vector<TopoDS_Shape>& bodies, const std::vector<TopoDS_Shape>& sheets,
                            double tol, WorkBudget& deadline, const Follow& follow, Preparation& info) {
  // The bodies are one argument: the fuse intersects only shapes of
  // different arguments, so bodies already united (or left apart for the
  // mesh-level union) are not intersected with each other again.
  TopoDS_Compound all_bodies;
  BRep_Builder builder;
  builder.MakeCompound(all_bodies);
  for (const auto& s : bodies) builder.Add(all_bodies, s);
  std::vector<TopoDS_Shape> parts{all_bodies};
  parts.insert(parts.end(), sheets.begin(), sheets.end());
  const double seconds = deadline.remaining();
  const FuseStep step = fuse_in_child(parts, seconds, [&](bool parallel) {
    FuseStep out;
    TopTools_ListOfShape args;
    for (const auto& p : parts) args.Append(p);
    BOPAlgo_Builder fuse;
    fuse.SetArguments(args);
    fuse.SetRunParallel(parallel);
    Handle(DeadlineIndicator) stop = new DeadlineIndicator(seconds);
    try {
      fuse.Perform(stop->Start());
    } catch (const Standard_Failure&) {
      fuse.AddError(new BOPAlgo_AlertBuilderFailed);
    }
    if (fuse.HasErrors() || fuse.Shape().IsNull()) {
      out.failure = stop->UserBreak() ? "the sheets could not be imprinted within the preparation's time"
                                      : "the sheets could not be imprinted";
      return out;
    }
    for (const auto& p : parts)
      for (const auto& f : faces_of(p))
        for (const auto& piece : pieces_of(fuse, f)) out.pieces.emplace_back(f, piece);
    out.shape = fuse.Shape();
    return out;
  });
  deadline.add(step.worked);
  if (step.shape.IsNull()) {
    info.fallback = step.failure;
    return {};
  }
  std::vector<TopoDS_Shape> solids;
  for (const auto& s : bodies)
    for (TopExp_Explorer ex(s, TopAbs_SOLID); ex.More(); ex.Next()) solids.push_back(ex.Current());
  TopTools_MapOfShape sheet_faces, dropped;
  for (const auto& s : sheets)
    for (const auto& f : faces_of(s)) sheet_faces.Add(f);
  // Sheet pieces inside a body (or on its surface) go; every other piece keeps its source.
  const Solids inside(solids, tol);
  for (const auto& [f, piece] : step.pieces) {
    if (sheet_faces.Contains(f) && inside.hold(piece)) dropped.Add(piece);
    else follow(f, piece);
  }
  info.sheets_imprinted = static_cast<int>(sheets.size());
  info.sheet_pieces_dropped = dropped.Extent();
  TopoDS_Compound out;
  BRep_Builder b;
  b.MakeCompound(out);
  TopTools_MapOfShape added;
  for (TopExp_Explorer ex(step.shape, TopAbs_FACE); ex.More(); ex.Next())
    if (!dropped.Contains(ex.Current()) && added.Add(ex.Current())) b.Add(out, ex.Current());
  return out;
}

}  // namespace detail

using detail::FaceList;

FaceList pieces_of(BOPAlgo_Builder& fuse, const TopoDS_Face& f) {  // history queries are not const in OCCT
  FaceList out;
  for (const auto& p : fuse.Modified(f)) out.push_back(TopoDS::Face(p));
  if (out.empty() && !fuse.IsDeleted(f)) out.push_back(f);
  return out;
}

}  // namespace sizemesh
