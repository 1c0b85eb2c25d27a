// User controls of the size map (paper 3.4): global phi_c, mu_d, beta, h_min,
// h_max; local phi_c per curve or face; local mu_d and beta per face; a
// prescribed size (number or expression of x, y, z) per point, curve or face.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/size_field.h"
#include "sizing/sources.h"
#include "topology/wing_features.h"

namespace sizemesh {

// A prescribed size: a number, or a muparser expression of x, y, z.
struct UserSize {
  double value = 0;
  std::string expression;  // used when not empty
};

// Which gaps the proximity size resolves: across the fluid (between parts, a
// slot between a flap and a wing), across the solid (a plate's thickness), or
// both. Auto: fluid for a closed model (cad/prepare.h makes aircraft
// closed; a solid with cavities is a flow domain, its fluid inside), both
// otherwise.
enum class GapSide { Auto, Fluid, Solid, Both };
const char* gap_side_name(GapSide s);
GapSide gap_side_from(const std::string& name);  // throws Error on an unknown name

struct SizingParams {
  double phi_c_deg = 15.0;  // curvature: central angle per element (degrees)
  double mu_d = 2.0;        // proximity: elements across a proximity distance
  double beta = 1.2;        // gradation: growth factor per element
  double h_min = 0;         // 0: h_min_rel * bounding-box diagonal
  double h_max = 0;         // 0: h_max_rel * bounding-box diagonal
  double h_min_rel = 5e-4;
  double h_max_rel = 0.05;
  double deviation = 0;     // curvature: largest distance of the mesh off the surface (model units); 0: none
  bool proximity = true;        // all proximity sizes: face width, curve length and gaps (paper 3.2.2)
  bool local_proximity = true;  // thin gaps between faces (beyond the paper)
  GapSide gap_side = GapSide::Auto;
  bool composite = true;          // mesh faces joined across smooth curves as one (topology/)
  double feature_angle_deg = 30;  // a curve the surface turns across by more is a feature, kept
  bool refine_background = true;  // split background edges too long to carry a graded size (beyond the paper)
  double max_triangles = 2e7;     // work budget: a size map asking for more triangles is refused before meshing
  std::map<int, double> curve_phi_c_deg, face_phi_c_deg, face_mu_d, face_beta;
  std::map<int, UserSize> point_size, curve_size, face_size;
  // Chordwise spacing at leading and trailing edges, as a share of the local
  // chord (0: off); --aero sets both to 0.001, the workshops' medium grid.
  double le_spacing = 0, te_spacing = 0;
  static constexpr double kAeroSpacing = 0.001;
  // Elements across a blunt trailing edge's base (0: off): its width there
  // over this count, on the base and its creases; --aero sets 4.
  double te_cells = 0;
  static constexpr double kAeroTeCells = 4;
  // Size on a wing's tip caps as a share of the tip's chord (0: off).
  double tip_spacing = 0;
  // The wing features of the model (topology/wing_features.h), found with
  // the composite faces; the spacings above act on their curves.
  WingFeatures wing;
  // Regions of space with their own size (sizing/sources.h): the config's
  // "sources" and the command line's --source, all of them.
  std::vector<SizeSource> sources;
  // Largest size per face in place of h_max (the far field and the symmetry
  // plane grade up to their own size); a vertex takes the least of its faces'.
  std::map<int, double> face_h_max;
  // Faces graded along background edges only (Eq. 12 without Eq. 11): the far
  // field and the symmetry plane, whose planar tessellation spans many body
  // diagonals in slivers too thin for a gradient to mean anything.
  std::set<int> edge_graded_faces;
  // From the composite faces (topology/): curves the mesh crosses bound no
  // face's width and set no length ([c - 1], 1 virtual); a feature curve's
  // length is its composite curve's ([c - 1]). Empty: every curve is real.
  std::vector<char> virtual_curve;
  std::vector<double> chain_length;
  bool crossed(int curve) const {
    return curve >= 1 && curve <= static_cast<int>(virtual_curve.size()) && virtual_curve[curve - 1];
  }

  // phi_c (degrees) on a face or curve: its local value, else the global one.
  double face_phi_c(int face) const { return local_or(face_phi_c_deg, face, phi_c_deg); }
  double curve_phi_c(int curve) const { return local_or(curve_phi_c_deg, curve, phi_c_deg); }

  // Absolute bounds for a model of this bounding-box diagonal.
  double resolved_h_min(double diagonal) const { return h_min > 0 ? h_min : h_min_rel * diagonal; }
  double resolved_h_max(double diagonal) const { return h_max > 0 ? h_max : h_max_rel * diagonal; }

 private:
  static double local_or(const std::map<int, double>& m, int id, double fallback) {
    const auto it = m.find(id);
    return it == m.end() ? fallback : it->second;
  }
};

// Throws Error (one sentence) on values outside their domain or ids the model
// does not have. Counts are the model's numbers of points, curves and faces.
void validate(const SizingParams& p, double diagonal, int points, int curves, int faces);

// Config entries address the sewn model's faces (1..sewn_faces); the prepared
// model's face f (1-based) came from face source[f - 1] and inherits its
// entries. Throws Error on ids outside 1..sewn_faces.
void remap_face_ids(SizingParams& p, const std::vector<int>& source, int sewn_faces);

// The far field and the symmetry plane (`domain_faces`) grade up to their own
// size, `element_size`, along background edges only (face_h_max,
// edge_graded_faces); nothing when element_size is not positive.
void size_domain_faces(SizingParams& p, const std::vector<int>& domain_faces, double element_size);

// The accuracy rules a size map built from p hands the mesher (SizeField::
// set_accuracy) for a model of `faces` faces whose map has the floor h_min:
// p's deviation bound, phi_c per face in radians (the turn an inner edge may
// make), ln(beta) per face (the gradient bound along a junction).
AccuracyRules accuracy_rules(const SizingParams& p, double h_min, int faces);

// Reads a JSON config into p (keys absent from the file keep p's values).
// Throws Error on unreadable or malformed files and unknown keys.
void read_config(const std::string& path, SizingParams& p);

}  // namespace sizemesh
