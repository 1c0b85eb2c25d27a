// The union of the closed components, one at a time (cad/occt_model.h).
//
// Components are grouped by overlapping bounding boxes (components that
// touch nothing are bodies of their own and need no Boolean), and each group
// is united one component at a time, largest first. Each step is the general
// fuse of the union so far with one component (BOPAlgo_CellsBuilder, all
// cells kept as one material, internal boundaries removed), kept only when
// the result is a valid shape with no free curve. A step that fails is tried
// again with a fuzzy value, then on the component healed by ShapeFix; one
// that still fails leaves that component out of the union, named in the
// report, and the others go on. Every attempt runs under the preparation's
// budget of work (cad/deadline.h): past it, the algorithm is told to stop.
#include <BOPAlgo_CellsBuilder.hxx>
#include <BRep_Builder.hxx>
#include <BRepBndLib.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepCheck_ListOfStatus.hxx>
#include <BRepCheck_Result.hxx>
#include <BRepLib.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <Bnd_Box.hxx>
#include <ShapeBuild_ReShape.hxx>
#include <ShapeFix_Shape.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>

#include <algorithm>
#include <map>
#include <iomanip>
#include <numeric>
#include <sstream>

#include "cad/deadline.h"
#include "cad/occt_model.h"

namespace sizemesh {
namespace {

// The general fuse's solids, each bounded by its outer shell alone and
// oriented outward. Components that together enclose a pocket of air leave it
// as an inner shell: no flow reaches it, so it is no wetted surface.
TopoDS_Shape outer_solids(const TopoDS_Shape& fused, int& pocket_faces) {
  if (fused.IsNull()) return fused;
  TopoDS_Compound out;
  BRep_Builder b;
  b.MakeCompound(out);
  for (TopExp_Explorer ex(fused, TopAbs_SOLID); ex.More(); ex.Next()) {
    TopoDS_Solid solid = TopoDS::Solid(ex.Current());
    TopTools_IndexedMapOfShape shells;
    TopExp::MapShapes(solid, TopAbs_SHELL, shells);
    if (shells.Extent() > 1) {
      // A pocket lies inside the outer shell, so its box is the smaller one.
      int outer_index = 1;
      double largest = -1;
      for (int i = 1; i <= shells.Extent(); ++i) {
        Bnd_Box box;
        BRepBndLib::Add(shells(i), box, false);
        if (!box.IsVoid() && box.SquareExtent() > largest) largest = box.SquareExtent(), outer_index = i;
      }
      const TopoDS_Shell& outer = TopoDS::Shell(shells(outer_index));
      for (int i = 1; i <= shells.Extent(); ++i)
        if (!shells(i).IsSame(outer))
          for (TopExp_Explorer f(shells(i), TopAbs_FACE); f.More(); f.Next()) ++pocket_faces;
      solid = solid_from_shell(outer);
    } else if (!BRepCheck_Analyzer(solid).IsValid()) {
      BRepLib::OrientClosedSolid(solid);
    }
    if (!solid.IsNull()) b.Add(out, solid);
  }
  return out;
}

// What BRepCheck finds wrong with a shape, counted by kind ("2 self-intersecting
// wires"), or empty when it is valid.
std::string invalidity(const TopoDS_Shape& shape) {
  BRepCheck_Analyzer analyzer(shape);
  if (analyzer.IsValid()) return "";
  std::map<BRepCheck_Status, int> count;
  for (TopAbs_ShapeEnum kind : {TopAbs_VERTEX, TopAbs_EDGE, TopAbs_WIRE, TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID}) {
    TopTools_IndexedMapOfShape all;
    TopExp::MapShapes(shape, kind, all);
    for (int i = 1; i <= all.Extent(); ++i) {
      const Handle(BRepCheck_Result)& r = analyzer.Result(all(i));
      if (r.IsNull()) continue;
      for (BRepCheck_Status st : r->Status())
        if (st != BRepCheck_NoError) ++count[st];
      for (r->InitContextIterator(); r->MoreShapeInContext(); r->NextShapeInContext())
        for (BRepCheck_Status st : r->StatusOnShape())
          if (st != BRepCheck_NoError) ++count[st];
    }
  }
  static const std::map<BRepCheck_Status, const char*> names = {
      {BRepCheck_SelfIntersectingWire, "self-intersecting wire"},
      {BRepCheck_IntersectingWires, "pair of intersecting wires"},
      {BRepCheck_InvalidCurveOnSurface, "curve off its surface"},
      {BRepCheck_InvalidPointOnCurveOnSurface, "vertex off its curve"},
      {BRepCheck_BadOrientationOfSubshape, "badly oriented shell"},
      {BRepCheck_NotClosed, "open wire or shell"},
      {BRepCheck_InvalidToleranceValue, "invalid tolerance"}};
  std::string out;
  for (const auto& [status, n] : count) {
    const auto it = names.find(status);
    out += (out.empty() ? "" : ", ") + std::to_string(n) + " " +
           (it == names.end() ? "BRepCheck status " + std::to_string(static_cast<int>(status)) : it->second);
  }
  return out;
}

// The general fuse of `parts` as one solid, within `seconds` of work (as far
// as the fuse listens; cad/deadline.h), on `parallel` threads.
FuseStep fuse_here(const std::vector<TopoDS_Shape>& parts, double fuzzy, double seconds, bool parallel) {
  FuseStep out;
  try {
    BOPAlgo_CellsBuilder cells;
    TopTools_ListOfShape args;
    for (const auto& p : parts) args.Append(p);
    cells.SetArguments(args);
    cells.SetRunParallel(parallel);
    cells.SetNonDestructive(true);
    cells.SetUseOBB(true);
    if (fuzzy > 0) cells.SetFuzzyValue(fuzzy);
    Handle(DeadlineIndicator) stop = new DeadlineIndicator(seconds);
    cells.Perform(stop->Start());
    if (cells.HasErrors()) {
      out.out_of_time = stop->why();
      out.failure = "the general fuse " + (out.out_of_time.empty() ? std::string("failed") : out.out_of_time);
      return out;
    }
    cells.AddAllToResult(1, false);
    cells.RemoveInternalBoundaries();
    TopoDS_Shape shape = outer_solids(cells.Shape(), out.pocket_faces);
    if (shape.IsNull()) {
      out.failure = "the general fuse gave nothing";
      return out;
    }
    // A free curve is a face missing, which no healing below adds: counted
    // first, it spares a failing union its whole-shape check and healing.
    if (const int free = count_free_curves(shape); free != 0) {
      out.failure = "the union has " + std::to_string(free) + " free curves";
      return out;
    }
    // Faces of the result a healing replaced (orientation within a shell, wires).
    Handle(ShapeBuild_ReShape) fixes;
    if (!invalidity(shape).empty()) {
      ShapeFix_Shape fix(shape);
      fix.Perform();
      fixes = fix.Context();
      shape = fix.Shape();
    }
    if (const std::string why = invalidity(shape); !why.empty()) {
      out.failure = "the union is not a valid shape: " + why;
      return out;
    }
    if (const int free = count_free_curves(shape); free != 0) {
      out.failure = "the union has " + std::to_string(free) + " free curves";
      return out;
    }
    for (const TopoDS_Shape& s : parts)
      for (TopExp_Explorer ex(s, TopAbs_FACE); ex.More(); ex.Next()) {
        const TopoDS_Face& f = TopoDS::Face(ex.Current());
        for (const auto& piece : pieces_of(cells, f)) {
          const TopoDS_Shape fixed = fixes.IsNull() ? TopoDS_Shape(piece) : fixes->Value(piece);
          if (!fixed.IsNull() && fixed.ShapeType() == TopAbs_FACE) out.pieces.emplace_back(f, TopoDS::Face(fixed));
        }
      }
    out.shape = shape;
  } catch (const Standard_Failure& e) {
    out.failure = std::string("the general fuse failed: ") + e.GetMessageString();
  }
  return out;
}

// fuse_here in a child process, ended at `seconds` whether or not the fuse
// listens (cad/isolated_fuse.cpp).
FuseStep fuse(const std::vector<TopoDS_Shape>& parts, double fuzzy, double seconds) {
  return fuse_in_child(parts, seconds, [&](bool parallel) { return fuse_here(parts, fuzzy, seconds, parallel); });
}

// The component healed by ShapeFix (tolerances, wires, orientation), with
// each face's healed image in `pieces`; null when healing changed nothing or
// failed.
TopoDS_Shape healed(const TopoDS_Shape& s, double tol, std::vector<std::pair<TopoDS_Face, TopoDS_Face>>& pieces) {
  try {
    ShapeFix_Shape fix(s);
    fix.SetPrecision(tol);
    fix.SetMaxTolerance(10 * tol);
    fix.Perform();
    const TopoDS_Shape out = fix.Shape();
    if (out.IsNull() || out.IsSame(s) || !TopExp_Explorer(out, TopAbs_SOLID).More()) return {};
    for (TopExp_Explorer ex(s, TopAbs_FACE); ex.More(); ex.Next()) {
      const TopoDS_Shape image = fix.Context()->Value(ex.Current());
      if (!image.IsNull() && image.ShapeType() == TopAbs_FACE)
        pieces.emplace_back(TopoDS::Face(ex.Current()), TopoDS::Face(image));
    }
    return out;
  } catch (const Standard_Failure&) {
    return {};
  }
}

Bnd_Box box_of(const TopoDS_Shape& s, double gap) {
  Bnd_Box b;
  BRepBndLib::Add(s, b, false);
  b.Enlarge(gap);
  return b;
}

}  // namespace

TopoDS_Shape unite_solids(const std::vector<TopoDS_Shape>& solids, const std::vector<int>& component, double tol,
                          WorkBudget& deadline, bool meshes_take_over, const Follow& follow,
                          const ProgressSink& progress, Preparation& info) {
  // Largest first: the fuselage, then what is attached to it.
  std::vector<Bnd_Box> box(solids.size());
  std::vector<size_t> order(solids.size());
  std::iota(order.begin(), order.end(), 0);
  for (size_t i = 0; i < solids.size(); ++i) box[i] = box_of(solids[i], tol);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return box[a].SquareExtent() > box[b].SquareExtent(); });

  TopoDS_Compound out;
  BRep_Builder builder;
  builder.MakeCompound(out);
  // All at once first (one fuse is cheaper than a chain of them), within
  // three quarters of the budget; one at a time when that fails, unless it
  // ran out of time (or was stopped as on course to) and the union of meshes
  // takes what is left.
  if (progress) progress("uniting " + std::to_string(solids.size()) + " components at once");
  const double allotted = 0.75 * deadline.remaining();
  const double before = deadline.spent();
  FuseStep all = fuse(solids, 0.0, allotted);
  deadline.add(all.worked);
  if (!all.shape.IsNull()) {
    for (const auto& [from, to] : all.pieces) follow(from, to);
    for (int k : component) info.components[k].route = "B-rep union";
    info.pocket_faces_removed = all.pocket_faces;
    info.solids_fused = static_cast<int>(solids.size());
    info.fused = true;
    return all.shape;
  }
  if (meshes_take_over && (!all.out_of_time.empty() || deadline.spent() - before >= 0.95 * allotted)) {
    std::ostringstream why;
    why << "not united: the B-rep union of all " << solids.size() << " components ";
    if (all.out_of_time.empty())
      why << "did not end within " << std::setprecision(3) << allotted << " s";
    else
      why << all.out_of_time;
    for (size_t i = 0; i < solids.size(); ++i) {
      info.components[component[i]].route = why.str();
      info.not_united.push_back(component[i] + 1);
      builder.Add(out, solids[i]);
    }
    return out;
  }
  std::vector<bool> done(solids.size(), false);
  size_t left = solids.size();
  for (size_t seed : order) {
    if (done[seed]) continue;
    // One group: the seed, then every component whose box meets the group's.
    TopoDS_Shape group = solids[seed];
    Bnd_Box group_box = box[seed];
    done[seed] = true;
    --left;
    int members = 1;
    for (bool grew = true; grew;) {
      grew = false;
      for (size_t k : order) {
        if (done[k] || group_box.IsOut(box[k])) continue;
        done[k] = true;
        --left;
        grew = true;
        Component& c = info.components[component[k]];
        if (progress) progress("uniting component " + std::to_string(component[k] + 1));
        // Each component gets an equal share of what is left, at least half a second.
        const double budget = std::min(deadline.remaining(), std::max(0.5, deadline.remaining() / (left + 1)));
        FuseStep step;
        std::vector<std::pair<TopoDS_Face, TopoDS_Face>> healing;
        struct Route {
          const char* name;
          bool heal;
          double fuzzy;
        };
        for (const Route& r : {Route{"B-rep union", false, 0.0}, Route{"B-rep union, fuzzy", false, tol},
                               Route{"B-rep union, healed", true, tol}}) {
          if (deadline.passed()) {
            step.failure = "the preparation's time ran out";
            break;
          }
          healing.clear();
          const TopoDS_Shape part = r.heal ? healed(solids[k], tol, healing) : solids[k];
          if (part.IsNull()) continue;
          step = fuse({group, part}, r.fuzzy, std::min(budget, deadline.remaining()));
          deadline.add(step.worked);
          if (!step.shape.IsNull()) {
            c.route = r.name;
            break;
          }
        }
        if (step.shape.IsNull()) {
          c.route = "not united: " + step.failure;
          info.not_united.push_back(component[k] + 1);
          builder.Add(out, solids[k]);
          continue;
        }
        info.pocket_faces_removed += step.pocket_faces;
        for (const auto& [from, to] : healing) follow(from, to);
        for (const auto& [from, to] : step.pieces) follow(from, to);
        group = step.shape;
        group_box.Add(box[k]);
        ++members;
      }
    }
    bool touches = false;
    for (size_t k = 0; k < solids.size(); ++k) touches = touches || (k != seed && !box[seed].IsOut(box[k]));
    info.components[component[seed]].route =
        members > 1 ? "B-rep union" : touches ? "the base others join" : "alone: touches no other component";
    if (members > 1) info.solids_fused += members;
    for (TopExp_Explorer ex(group, TopAbs_SOLID); ex.More(); ex.Next()) builder.Add(out, ex.Current());
  }
  info.fused = info.solids_fused > 0;
  return out;
}

}  // namespace sizemesh
