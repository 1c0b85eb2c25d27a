#include "app/cli_options.h"

#include <chrono>
#include <cstdlib>
#include <iostream>

#include <cmath>

#include "sizing/options.h"
#include "sizing/sources.h"

namespace sizemesh {

namespace {
// CLI11's own range check prints the whole double range; say it plainly.
// A number that `ok` accepts, or "must be <what>, got '...'".
CLI::Validator number_check(const std::string& what, const std::string& name, bool (*ok)(double)) {
  return CLI::Validator(
      [what, ok](std::string& s) -> std::string {
        try {
          size_t pos = 0;
          const double v = std::stod(s, &pos);
          if (pos == s.size() && ok(v)) return {};
        } catch (const std::logic_error&) {  // not a number, or out of double's range
        }
        return "must be " + what + ", got '" + s + "'";
      },
      name);
}
const auto positive = number_check("a positive number", "POSITIVE", [](double v) { return v > 0 && v < 1e300; });
const auto finite_number = number_check("a finite number", "NUMBER", [](double v) { return std::abs(v) < 1e300; });
}  // namespace

void add_run_options(CLI::App& app, RunCommandLine& cl) {
  app.add_option("model", cl.options.input, "CAD model: .step/.stp, .iges/.igs or .brep")->required();
  app.add_option("-o,--output", cl.options.output, "output surface mesh: .vtu (ParaView), .msh (Gmsh 4.1), .stl, .cgns (CFD solvers), .mesh (Medit, Mmg) or .smesh (TetGen)");
  app.add_option("--report", cl.options.report, "write a JSON report: counts, quality, conformity, timings, failed faces");
  app.add_option("--family", cl.options.family,
                 "write a mesh family for grid convergence: N levels OUT.L1.ext (coarsest) .. OUT.LN.ext from one "
                 "size map scaled per level (reports likewise), instead of OUT")
      ->check(CLI::Range(1, 8));
  app.add_option("--family-ratio", cl.options.family_ratio,
                 "triangles of each family level against the previous one (sizes scale by its inverse square root)")
      ->capture_default_str()
      ->check(CLI::Range(1.1, 16.0));
  app.add_option("--threads", cl.options.meshing.threads, "threads for meshing faces (0: all cores); the mesh is the same")
      ->capture_default_str()->check(CLI::Range(0, 1024));
  app.add_option("--background", cl.options.background, "write the background mesh with its size fields (.vtu)");
  app.add_flag("--info", cl.info_only, "print what was loaded (unit, bounding box, entity counts, free curves) and exit");
  app.add_flag("!--no-sew", cl.options.load.sew, "do not sew faces that touch");
  app.add_flag("!--no-union", cl.options.load.unite,
               "mesh each component where it lies: no repair of open components, no union of the closed ones");
  app.add_option("--union-seconds", cl.options.load.union_seconds,
                 "work budget of the union of components in CPU seconds, so a loaded machine takes the same routes (default "
                 "1.5 s per component, 4 to 8 s, repair included; with a far field or symmetry plane 4 s per component, "
                 "at least 12; stopped all the same at 3 times it in wall time); an attempt past it is abandoned and the "
                 "components it leaves out are named (exit 3)")
      ->check(CLI::Range(0.1, 3600.0));
  app.add_option("--mesh-union", cl.mesh_union,
                 "unite these components (numbers as --info lists them, comma-separated, or 'all') as meshes: their "
                 "triangles are cut with the rest's and the cut nodes put on both CAD surfaces; no B-rep union is tried")
      ->delimiter(',')
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            if (v == "all") return {};
            char* end = nullptr;
            const long k = std::strtol(v.c_str(), &end, 10);
            return !v.empty() && *end == 0 && k >= 1 && k <= 1000000 ? "" : "'" + v + "' is not a component number or 'all'";
          },
          "NUMBERS|all"));
  app.add_option("--sew-tolerance", cl.options.load.sewing_tolerance_rel, "sewing tolerance relative to the bounding-box diagonal")
      ->capture_default_str()->check(positive);
  app.add_option("--deflection", cl.options.tessellation.deflection_rel,
                 "background tessellation: chordal deflection relative to the bounding-box diagonal")
      ->capture_default_str()->check(positive);
  app.add_option("--angle", cl.options.tessellation.angle_deg, "background tessellation: angular deflection in degrees")
      ->capture_default_str()->check(CLI::Range(0.1, 90.0));
  const auto* domain = "flow domain (faces marked 'farfield' and 'symmetry' in every output format)";
  app.add_option("--farfield", cl.farfield, "outer boundary around the body: none, sphere or box")
      ->capture_default_str()->check(CLI::IsMember({"none", "sphere", "box"}))->group(domain);
  app.add_option("--farfield-size", cl.options.load.domain.size,
                 "far-field radius (sphere) or half side (box), centred on the body (default 20 body diagonals)")
      ->check(positive)->group(domain);
  app.add_option("--farfield-h", cl.options.load.domain.element_size, "element size on the far field (default a tenth of its size)")
      ->check(positive)->group(domain);
  cl.symmetry_at = app.add_option("--symmetry-at", cl.options.load.domain.symmetry_at,
                            "coordinate of the symmetry plane (default 0, or the body's side nearest to 0)")
                 ->check(finite_number)->group(domain);
  app.add_option("--symmetry", cl.symmetry,
                 "half model: cut the body and the far field at the plane x, y or z = --symmetry-at, keep the "
                 "larger side")
      ->capture_default_str()->check(CLI::IsMember({"none", "x", "y", "z"}))->group(domain);
  auto* sizing = "sizing (paper 3.4; h_min/h_max default to 5e-4 and 0.05 of the bounding-box diagonal)";
  for (const SizingOption& opt : sizing_options()) {
    CLI::Option* cli = nullptr;
    if (opt.on) {
      cli = app.add_flag("!" + opt.flag, cl.options.sizing.*opt.on, opt.help);
    } else if (opt.number) {
      cli = app.add_option(opt.flag, cl.options.sizing.*opt.number, opt.help);
      if (cl.options.sizing.*opt.number != 0) cli->capture_default_str();
    } else {
      cl.words[opt.key] = opt.get(cl.options.sizing);
      cli = app.add_option(opt.flag, cl.words[opt.key], opt.help)->capture_default_str()->check(CLI::IsMember(opt.choices));
    }
    if (opt.cli_lo < opt.cli_hi) cli->check(CLI::Range(opt.cli_lo, opt.cli_hi));
    cli->group(sizing);
  }
  app.add_option("--source", cl.sources,
                 "a region with its own element size, repeatable: 'box XMIN YMIN ZMIN XMAX YMAX ZMAX H [GROW]', "
                 "'sphere|point X Y Z R H [GROW]', 'line|cylinder X0 Y0 Z0 X1 Y1 Z1 R H [GROW]' (model units; the "
                 "size grows to h_max over GROW, else at beta)")
      ->check(CLI::Validator(
          [](std::string& text) {
            try {
              parse_source(text);
              return std::string();
            } catch (const Error& e) {
              return std::string(e.what());
            }
          },
          "SOURCE", "size source"))
      ->group(sizing);
  app.add_flag("--aero", cl.aero,
               "the gridding workshops' defaults: --le-spacing and --te-spacing 0.001 (0.1% of the local chord) "
               "and --te-cells 4 where not given (with the default beta, 1.2, the workshops' growth bound)")
      ->group(sizing);
  app.add_option("--config", cl.options.config,
                 "JSON config: the globals above and local phi_c, mu_d, beta, sizes per point/curve/face "
                 "(see examples/sizing.json); a flag given on the command line wins over the file")->group(sizing);
  app.add_option("--smoother", cl.smoother, "edge-gradation solver: exact (Dijkstra) or lpsolve (reference LP)")
      ->capture_default_str()->check(CLI::IsMember({"exact", "lpsolve"}))->group(sizing);
  app.add_flag("-q,--quiet", [&cl](int64_t) { cl.options.verbose = false; }, "print nothing but errors");
}

void finish_run_options(const CLI::App& app, RunCommandLine& cl) {
  RunOptions& o = cl.options;
  o.edge_solver = cl.smoother == "lpsolve" ? EdgeSolver::LpSolve : EdgeSolver::Dijkstra;
  using FF = FlowDomainOptions::FarField;
  o.load.domain.farfield = cl.farfield == "sphere" ? FF::Sphere : cl.farfield == "box" ? FF::Box : FF::None;
  o.load.domain.symmetry_axis = cl.symmetry == "none" ? -1 : cl.symmetry[0] - 'x';
  o.load.domain.symmetry_at_given = cl.symmetry_at->count() > 0;
  o.load.mesh_union.clear();
  for (const std::string& v : cl.mesh_union)
    if (v == "all") o.load.mesh_union_all = true;
    else o.load.mesh_union.push_back(std::stoi(v));
  if (o.verbose) {
    // The union's progress, once loading has taken more than a second.
    const auto start = std::chrono::steady_clock::now();
    o.load.progress = [start](const std::string& line) {
      if (std::chrono::steady_clock::now() - start > std::chrono::seconds(1)) std::cerr << "sizemesh: " << line << "\n";
    };
  }
  for (const std::string& text : cl.sources) o.sizing.sources.push_back(parse_source(text));
  if (cl.aero) {
    if (app.count(flag_of("le_spacing")) == 0) o.sizing.le_spacing = SizingParams::kAeroSpacing;
    if (app.count(flag_of("te_spacing")) == 0) o.sizing.te_spacing = SizingParams::kAeroSpacing;
    if (app.count(flag_of("te_cells")) == 0) o.sizing.te_cells = SizingParams::kAeroTeCells;
  }
  for (const SizingOption& opt : sizing_options()) {
    if (opt.set) opt.set(o.sizing, cl.words[opt.key]);
    if (app.count(opt.flag) > 0) o.sizing_from_cli.insert(opt.key);
  }
}

std::vector<std::string> arguments_for(const CLI::App& app,
                                       const std::vector<std::pair<std::string, std::string>>& kwargs) {
  std::vector<std::string> args;
  for (const auto& [name, value] : kwargs) {
    std::string flag = "--" + name;
    for (char& c : flag)
      if (c == '_') c = '-';
    const CLI::Option* opt = app.get_option_no_throw(flag);
    const CLI::Option* negated = app.get_option_no_throw("--no-" + flag.substr(2));
    const bool is_switch = value == "true" || value == "false";
    if (negated && is_switch) {  // sew=False -> --no-sew
      if (value == "false") args.push_back("--no-" + flag.substr(2));
    } else if (opt && opt->get_expected_max() == 0) {  // a flag of its own
      if (value != "false") args.push_back(flag);
    } else if (opt) {
      args.push_back(flag);
      args.push_back(value);
    } else {
      throw Error("unknown option '" + name + "'");
    }
  }
  return args;
}

}  // namespace sizemesh
