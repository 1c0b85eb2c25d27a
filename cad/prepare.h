// Geometry preparation between loading and the background mesh: the sewn
// model's components, their repair, and their union into one wetted surface.
// Kernel-free description of what was done; the work starts in cad/prepare.cpp.
#pragma once

#include <string>
#include <vector>

#include "core/types.h"

namespace sizemesh {

// What a face bounds, for the solver: the body (a wall), the outer boundary
// of the flow domain, or the symmetry plane of a half model.
enum class Boundary { Wall, Farfield, Symmetry };

// One connected piece of the sewn model (a shell, or a face on its own).
struct Component {
  int faces = 0;
  bool closed = false;    // no free curves: it bounds a volume
  int free_curves = 0;
  double area = 0;
  Vec3 bbox_min, bbox_max;
  // After repair: "solid" (closed, takes part in the union), "sheet" (open,
  // meshed where it lies).
  std::string role;
  // How it joined the wetted surface: "B-rep union" (also ", fuzzy" and
  // ", healed"), "the base others join" (no other component joined it as a
  // B-rep; others may at mesh level), "alone: ..." (it touches no other
  // component), "imprinted"
  // (a sheet cut where it meets the bodies), "mesh-level union" (its mesh cut
  // with the rest's, mesher/mesh_union.h), or "not united: <why>" (meshed
  // where it lies; the run ends with exit 3).
  std::string route;
  // Why the B-rep union did not take it, when the union of meshes then did
  // (the route it had before: "not united: <why>", without its first words).
  std::string brep_failure;
  int faces_removed = 0;  // duplicate or internal faces taken out by the repair
  int caps_added = 0;     // planar faces closing its flat open loops (a tip, a root)
  std::vector<int> face_ids;  // its faces' ids in the sewn model (Model::source_face)
};

struct Preparation {
  bool union_requested = false;
  bool union_skipped = false;  // requested, but only the description was asked for (--info)
  std::vector<Component> components;  // as sewn, before repair
  int duplicate_faces_removed = 0;    // coincident face pairs inside one component
  int internal_faces_removed = 0;     // sheets lying inside their own component's volume
  int components_repaired = 0;        // open components closed by the repair
  int caps_added = 0;                 // planar caps over flat open loops
  int half_model_axis = -1;           // 0-2: a half model, open on the plane x, y or z = 0; -1 not
  int solids_fused = 0;               // closed components merged by the union
  bool fused = false;                 // the union ran and its result was kept
  int pocket_faces_removed = 0;       // faces of air pockets the union enclosed (no flow reaches them)
  int sheets_imprinted = 0;           // open components joined to the rest by the general fuse
  int sheet_pieces_dropped = 0;       // pieces of them inside a body
  std::string fallback;               // why the union was not kept; empty when it was or was not needed
  std::vector<int> not_united;        // components (1-based) left where they lie: the surface is not one
  std::vector<int> left_out;          // flat open disks a body passes through (actuator disks): no wall, not meshed
  std::vector<int> internal_sheets;   // open components lying inside a body or on its surface: not meshed
  int united_at_mesh_level = 0;       // components the B-rep union left out, united as meshes
  double seconds_budget = 0;          // the union's time budget
  int faces_split_at_folds = 0;       // faces split along a knot line where they fold within an element
  int strip_faces_collapsed = 0;      // faces narrower than twice the sewing tolerance made one curve
  int small_loops_dropped = 0;        // closed edges shorter than the sewing tolerance
  int faces_made_planar = 0;          // faces whose flat B-spline (or other) surface became a plane
  int edges_made_real = 0;            // degenerated edges the surface maps onto a line, made real edges there
  int faces_before = 0, faces_after = 0;
  // Wall time of each step: repair of the components (with their checks),
  // union of the closed ones, imprint of the open ones, and the last splits
  // at folds and onto planes.
  double repair_seconds = 0, union_seconds = 0, imprint_seconds = 0, finish_seconds = 0;
};

}  // namespace sizemesh
