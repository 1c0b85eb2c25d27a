#include "sizing/options.h"

namespace sizemesh {

const std::vector<SizingOption>& sizing_options() {
  using P = SizingParams;
  static const std::vector<SizingOption> table = {
      {"phi_c", "--phi-c", &P::phi_c_deg, nullptr, {}, "curvature: central angle per element, degrees, in (0, 180)"},
      {"mu_d", "--mu-d", &P::mu_d, nullptr, {}, "proximity: elements across a thin region, > 0"},
      {"beta", "--beta", &P::beta, nullptr, {}, "gradation: largest size ratio between neighbouring elements, >= 1"},
      {"h_min", "--h-min", &P::h_min, nullptr, {}, "smallest element size (model units)"},
      {"h_max", "--h-max", &P::h_max, nullptr, {}, "largest element size (model units)"},
      {"deviation", "--deviation", &P::deviation, nullptr, {},
       "curvature: largest distance of the mesh off the surface (model units; 0: no bound)"},
      {"proximity", "--no-proximity", nullptr, &P::proximity, {},
       "size from curvature (and user sizes) alone: no face width, curve length or gap sizes"},
      {"local_proximity", "--no-gaps", nullptr, &P::local_proximity, {},
       "do not refine thin gaps between faces (plates, blunt trailing edges, part gaps)"},
      {"gap_side", "--gap-side", nullptr, nullptr, {"auto", "fluid", "solid", "both"},
       "gaps to resolve: fluid (between parts), solid (plate thickness), both; auto: fluid for a closed model, "
       "both for sheets and unsewn faces",
       0, 0, [](P& p, const std::string& w) { p.gap_side = gap_side_from(w); },
       [](const P& p) { return std::string(gap_side_name(p.gap_side)); }},
      {"composite", "--no-composite", nullptr, &P::composite, {},
       "mesh every B-rep face apart: no composite faces across smooth curves (narrow faces and short curves then set the mesh)"},
      {"feature_angle", "--feature-angle", &P::feature_angle_deg, nullptr, {},
       "a curve the surface turns across by more than this many degrees is a feature the mesh keeps; smoother ones "
       "are crossed by composite faces", 0.0, 180.0},
      {"refine_background", "--no-refine-background", nullptr, &P::refine_background, {},
       "keep the tessellation as the background mesh, even where its edges are too long for sizes to grow"},
      {"le_spacing", "--le-spacing", &P::le_spacing, nullptr, {},
       "size at leading edges as a share of the local chord (0.001: 0.1%), graded away at beta; 0: off", 0.0, 1.0},
      {"te_spacing", "--te-spacing", &P::te_spacing, nullptr, {},
       "size at trailing edges (sharp, and the creases of blunt ones) as a share of the local chord, graded away "
       "at beta; 0: off", 0.0, 1.0},
      {"te_cells", "--te-cells", &P::te_cells, nullptr, {},
       "elements across a blunt trailing edge's base (its local width over this count, on the base and its "
       "creases), graded away at beta; 0: off", 0.0, 1000.0},
      {"tip_spacing", "--tip-spacing", &P::tip_spacing, nullptr, {},
       "size on wing tip caps (their faces and edges) as a share of the tip chord, graded away at beta; 0: off",
       0.0, 1.0},
      {"max_triangles", "--max-triangles", &P::max_triangles, nullptr, {},
       "refuse, before meshing, a size map that asks for more triangles (an estimate from the map)", 1.0, 1e15},
  };
  return table;
}

const std::string& flag_of(const std::string& key) {
  for (const SizingOption& o : sizing_options())
    if (o.key == key) return o.flag;
  throw Error("no sizing option '" + key + "'");
}

std::string remedy(Limit l) {
  switch (l) {
    case Limit::HMax: return flag_of("h_max");
    case Limit::Curvature: return flag_of("phi_c") + " or " + flag_of("deviation");
    case Limit::FaceProximity:
    case Limit::CurveLength:
    case Limit::Gap: return flag_of("mu_d") + ", " + flag_of("local_proximity") + " or " + flag_of("h_min");
    case Limit::Thickness: return flag_of("gap_side") + " fluid, " + flag_of("mu_d") + " or " + flag_of("h_min");
    case Limit::User: return "the config's local sizes";
    case Limit::HMin: return flag_of("h_min");
    case Limit::FarField: return "";
    case Limit::Source: return "the sources' sizes";
    case Limit::Aero:
      return flag_of("le_spacing") + ", " + flag_of("te_spacing") + ", " + flag_of("te_cells") + " or " +
             flag_of("tip_spacing");
  }
  return flag_of("h_min");
}

void apply_config(const std::string& path, const std::set<std::string>& from_cli, SizingParams& p) {
  const SizingParams given = p;
  read_config(path, p);
  for (const SizingOption& o : sizing_options()) {
    if (!from_cli.count(o.key)) continue;
    if (o.number) p.*o.number = given.*o.number;
    if (o.on) p.*o.on = given.*o.on;
    if (o.set) o.set(p, o.get(given));
  }
}

}  // namespace sizemesh
