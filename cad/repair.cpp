// The repair of one open component (repair_component, cad/repair.h): its trials and what they may take out.
#include "cad/repair.h"

#include <BRepBuilderAPI_Copy.hxx>
#include <BRepGProp.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <functional>
#include <map>
#include <thread>

#include <tbb/task_arena.h>

#include "cad/coincident_faces.h"
#include "cad/deadline.h"
#include "cad/inside_solids.h"
#include "cad/occt_model.h"  // face_area_exact
#include "core/off_thread.h"

namespace sizemesh::detail {
namespace {

// Bounds on the repair's trials: sewing one component per trial.
constexpr int kMaxCandidates = 16;
constexpr int kMaxRounds = 8;

// Faces of `faces` whose sewn image has a free curve.
FaceList faces_on_free_curves(const FaceList& faces, const Sewn& s) {
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(s.shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  FaceList out;
  for (const auto& f : faces) {
    const TopoDS_Face g = s.after(f);
    for (TopExp_Explorer ex(g, TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
      const int k = edge_faces.FindIndex(e);
      if (k == 0 || BRep_Tool::Degenerated(e) || BRep_Tool::IsClosed(e, g)) continue;
      if (edge_faces(k).Extent() == 1) {
        out.push_back(f);
        break;
      }
    }
  }
  return out;
}

double volume_of(const TopoDS_Shape& solid) {
  GProp_GProps g;
  BRepGProp::VolumeProperties(solid, g);
  return std::abs(g.Mass());
}

// What one round of the repair may take out: each face on a free curve alone,
// and each connected group of them (faces sharing a curve in the sewing):
// a planform plane in pieces (one per wing segment and side) opens as much
// as it closes when one piece goes, and closes only when all go together.
std::vector<FaceList> removal_options(const FaceList& cand, const Sewn& s) {
  std::vector<FaceList> out;
  for (const auto& f : cand) out.push_back({f});
  std::vector<int> group(cand.size());
  for (size_t i = 0; i < cand.size(); ++i) group[i] = static_cast<int>(i);
  const std::function<int(int)> root = [&](int i) { return group[i] == i ? i : group[i] = root(group[i]); };
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(s.shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  for (size_t i = 0; i < cand.size(); ++i)
    for (size_t j = i + 1; j < cand.size(); ++j) {
      const TopoDS_Face a = s.after(cand[i]), b = s.after(cand[j]);
      bool touch = false;
      for (TopExp_Explorer ex(a, TopAbs_EDGE); ex.More() && !touch; ex.Next())
        for (TopExp_Explorer ey(b, TopAbs_EDGE); ey.More() && !touch; ey.Next()) touch = ex.Current().IsSame(ey.Current());
      if (touch) group[root(static_cast<int>(i))] = root(static_cast<int>(j));
    }
  std::map<int, FaceList> groups;
  for (size_t i = 0; i < cand.size(); ++i) groups[root(static_cast<int>(i))].push_back(cand[i]);
  for (const auto& [r, faces] : groups)
    if (faces.size() > 1) out.push_back(faces);
  return out;
}

double volume_of(const std::vector<TopoDS_Shape>& solids) {
  double v = 0;
  for (const auto& s : solids) v += volume_of(s);
  return v;
}

// Coincident faces or groups of `faces` taken out of `current` (sewn as `now` at
// tolerance t): both (the caps between two halves of one body) when that
// does not open the component further, else one of them (a duplicate).
// Returns the faces taken out. Given up once `stop` is set.
int drop_coincident(const FaceList& faces, const Coincident& pairs, double t, FaceList& current, Sewn& now,
                    const std::atomic<bool>* stop = nullptr) {
  int dropped = 0;
  for (const auto& [one, other] : pairs) {
    if (stop && *stop) break;
    FaceGroup both = one;
    both.insert(both.end(), other.begin(), other.end());
    for (const FaceGroup& drop : {both, other}) {
      FaceList trial;
      for (const auto& f : current)
        if (std::none_of(drop.begin(), drop.end(), [&](int d) { return f.IsSame(faces[d]); })) trial.push_back(f);
      Sewn s = sew(trial, t, stop);
      if (s.free_curves <= now.free_curves) {
        dropped += static_cast<int>(drop.size());
        current = trial;
        now = s;
        break;
      }
    }
  }
  return dropped;
}

}  // namespace

Repair repair_component(const FaceList& read, double tol, double component_diagonal, const HalfModelPlanes& half,
                        int cap_axis) {
  Repair r;
  // No closed component, with the work its trials took.
  const auto none = [&r] {
    Repair failed;
    failed.helper_work = r.helper_work;
    return failed;
  };
  const FaceList faces = split_pinched(read, tol, r.split);
  const auto pairs = coincident_pairs(faces, tol);
  // A looser sewing may close it alone (a sewing ladder up to 1e-3 of the
  // component's size), judged by the free curves left once coincident faces
  // (two halves' root caps, back to back) are out: kept, they would lie
  // inside the closed body.
  // The rest starts from the sewing at `tol` (the ladder's first rung).
  // The rungs are sewn in parallel: the first on the faces themselves, on
  // this thread; each other on a copy of them (sewing widens the tolerances
  // of what it sews), given up once the first closes the component. A later
  // rung that closes it is sewn again on the faces themselves, after the
  // first, as it would have been in turn.
  std::vector<double> rungs;
  for (double t : {tol, 10 * tol, 100 * tol})
    if (t == tol || t <= 1e-3 * component_diagonal) rungs.push_back(t);
  struct Rung {
    FaceList trial;
    Sewn sewn;
    int dropped = 0;
    bool closes = false;
  };
  std::atomic<bool> first_closes{false};
  const auto climb = [&](double t, const FaceList& own, const std::atomic<bool>* stop) {
    Rung r{own, sew(own, t, stop)};
    r.dropped = pairs.empty() ? 0 : drop_coincident(own, pairs, t, r.trial, r.sewn, stop);
    r.closes = r.sewn.free_curves == 0 && TopExp_Explorer(r.sewn.shape, TopAbs_SHELL).More();
    return r;
  };
  std::vector<Rung> climbed(rungs.size());
  std::vector<double> rung_work(rungs.size(), 0.0);  // CPU seconds of each later rung
  const auto later_rungs = [&] {
    off_this_thread(rungs.size() - 1, [&](size_t j) {
      timed(rung_work[j + 1], [&] {
        BRepBuilderAPI_Copy copy(compound_of(faces));
        FaceList own;
        for (const auto& f : faces) own.push_back(TopoDS::Face(copy.Modified(f).First()));
        climbed[j + 1] = climb(rungs[j + 1], own, &first_closes);
      });
    });
  };
  const auto first_rung = [&] {
    climbed[0] = climb(rungs[0], faces, nullptr);
    if (climbed[0].closes) first_closes = true;
  };
  if (tbb::this_task_arena::max_concurrency() > 1) {
    std::exception_ptr failure;
    std::thread beside([&] {
      try {
        later_rungs();
      } catch (...) {
        failure = std::current_exception();
      }
    });
    try {
      first_rung();
    } catch (...) {
      first_closes = true;
      beside.join();
      throw;
    }
    beside.join();
    if (failure) std::rethrow_exception(failure);
  } else {
    first_rung();
    later_rungs();
  }
  // The later rungs' work counts when they ran to the end (the first did
  // not close): abandoned ones got as far as timing let them.
  if (!climbed[0].closes)
    for (double w : rung_work) r.helper_work += w;
  for (size_t i = 0; i < rungs.size(); ++i) {
    if (!climbed[i].closes) continue;
    Rung c = i == 0 ? climbed[0] : climb(rungs[i], faces, nullptr);
    if (!c.closes) continue;
    r.closed = c.sewn.shape;
    r.sewn = c.sewn;
    r.kept = c.trial;
    r.duplicates = c.dropped;
    return r;
  }
  FaceList current = climbed[0].trial;
  Sewn now = climbed[0].sewn;
  r.duplicates = climbed[0].dropped;
  // Faces on free curves, best first, while each removal closes more. What
  // is taken out stays under half the component's area: an internal plane or
  // a cap, never the skin that bounds the body.
  FaceList removed;
  double area_left = 0, area_out = 0;
  for (const auto& f : current) area_left += face_area_exact(f);
  for (int round = 0; round < kMaxRounds && now.free_curves > 0; ++round) {
    FaceList cand = faces_on_free_curves(current, now);
    if (cand.size() > static_cast<size_t>(kMaxCandidates)) cand.resize(kMaxCandidates);
    const std::vector<FaceList> options = removal_options(cand, now);
    // Each option's trial, sewn on a copy of what it keeps, all in parallel:
    // sewing widens the tolerances of the curves and vertices it sews, so
    // trials on the faces themselves would change each other.
    struct Trial {
      FaceList faces;
      int free_curves = -1;  // -1: not tried
      double volume = -1;    // of the closed result, when it closes
    };
    std::vector<Trial> trials(options.size());
    std::vector<double> trial_work(options.size(), 0.0);
    off_this_thread(options.size(), [&](size_t c) {
      timed(trial_work[c], [&] {
        double out = 0;
        for (const auto& f : options[c]) out += face_area_exact(f);
        FaceList trial;
        for (const auto& f : current)
          if (std::none_of(options[c].begin(), options[c].end(), [&](const TopoDS_Face& g) { return g.IsSame(f); }))
            trial.push_back(f);
        if (trial.empty() || area_out + out > 0.5 * area_left) return;
        const Sewn s = sew(faces_of(BRepBuilderAPI_Copy(compound_of(trial)).Shape()), tol);
        trials[c].faces = std::move(trial);
        trials[c].free_curves = s.free_curves;
        if (s.free_curves == 0) {
          const std::vector<TopoDS_Shape> solids = solids_of(s.shape);
          if (!solids.empty()) trials[c].volume = volume_of(solids);
        }
      });
    });
    for (double w : trial_work) r.helper_work += w;
    int best = -1;
    for (size_t c = 0; c < options.size(); ++c) {
      const Trial& t = trials[c];
      if (t.free_curves < 0) continue;
      const int to_beat = best < 0 ? now.free_curves : trials[best].free_curves;
      // Removals that close it alike (a wing's upper skin, lower skin and
      // planform plane all meet on the leading and trailing edges: any two
      // close): the one that encloses the most keeps the skins, so what is
      // taken out is the plane inside them.
      if (t.free_curves < to_beat || (best >= 0 && t.free_curves == to_beat && t.volume > trials[best].volume))
        best = static_cast<int>(c);
    }
    // The best sewn again on the faces themselves: the sewing the rest goes on from.
    Sewn best_sewn;
    if (best >= 0) {
      best_sewn = sew(trials[best].faces, tol);
      if (best_sewn.free_curves >= now.free_curves) best = -1;
    }
    if (best < 0) break;
    for (const auto& g : options[best]) {
      removed.push_back(g);
      area_out += face_area_exact(g);
      current.erase(std::find_if(current.begin(), current.end(), [&](const TopoDS_Face& f) { return f.IsSame(g); }));
    }
    now = best_sewn;
  }
  // Flat loops left open (a tip or a root without its cap) get planar caps.
  if (now.free_curves > 0) {
    const Caps caps = planar_caps(now.shape, tol, half, cap_axis);
    r.half_model_axis = caps.half_model_axis;
    if (!caps.faces.empty()) {
      FaceList trial = joined(current, caps.faces);
      Sewn s = sew(trial, tol);
      if (s.free_curves < now.free_curves) {
        current = trial;
        now = s;
        r.caps = static_cast<int>(caps.faces.size());
      }
    }
  }
  // Open on its half-model plane alone: capped there for a moment, to tell
  // the faces taken out inside it from those outside, and kept open.
  std::vector<TopoDS_Shape> solids;
  if (now.free_curves != 0) {
    if (r.half_model_axis < 0) return none();
    const Sewn capped = sew(joined(current, planar_caps(now.shape, tol, half, r.half_model_axis).faces), tol);
    if (capped.free_curves != 0) return none();
    solids = solids_of(capped.shape);
    r.half_open = now.shape;
  } else {
    solids = solids_of(now.shape);
    r.closed = now.shape;
  }
  // A cap lying on a face (a planform plane and the cap over its rim) bounds no volume.
  if (solids.empty() || volume_of(solids) < 1e-6 * std::pow(component_diagonal, 3)) return none();
  const Solids inside(solids, tol);
  for (const auto& f : removed) {
    if (inside.hold(f)) ++r.internal;
    else r.sheets.push_back(f);
  }
  r.sewn = now;
  r.kept = current;
  return r;
}

}  // namespace sizemesh::detail
