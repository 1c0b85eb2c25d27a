// sizemesh: automatic element sizing and surface meshing of CAD models.
#include <CLI/CLI.hpp>

#include <cmath>
#include <iostream>
#include <map>
#include <string>

#include "sizing/options.h"
#include "src/info.h"
#include "src/pipeline.h"

namespace {
// CLI11's own range check prints the whole double range; say it plainly.
const auto positive = CLI::Validator(
    [](std::string& s) -> std::string {
      try {
        size_t pos = 0;
        const double v = std::stod(s, &pos);
        if (pos == s.size() && v > 0 && v < 1e300) return {};
      } catch (...) {
      }
      return "must be a positive number, got '" + s + "'";
    },
    "POSITIVE");
const auto finite_number = CLI::Validator(
    [](std::string& s) -> std::string {
      try {
        size_t pos = 0;
        const double v = std::stod(s, &pos);
        if (pos == s.size() && std::abs(v) < 1e300) return {};
      } catch (...) {
      }
      return "must be a finite number, got '" + s + "'";
    },
    "NUMBER");
}  // namespace

int main(int argc, char** argv) {
  using namespace sizemesh;
  RunOptions o;
  bool info_only = false;
  CLI::App app{
      "sizemesh: reads a STEP, IGES or BREP model and writes a triangular surface mesh whose element\n"
      "sizes follow the geometry (curvature, proximity, user sizes) with a bounded growth rate.\n"
      "Exit status: 0 success, 1 error (bad input or output), 2 bad command line, 3 partial mesh."};
  app.add_option("model", o.input, "CAD model: .step/.stp, .iges/.igs or .brep")->required();
  app.add_option("-o,--output", o.output, "output surface mesh: .vtu (ParaView), .msh (Gmsh 4.1) or .stl");
  app.add_option("--report", o.report, "write a JSON report: counts, quality, conformity, timings, failed faces");
  app.add_option("--threads", o.meshing.threads, "threads for meshing faces (0: all cores); the mesh is the same")
      ->capture_default_str()->check(CLI::Range(0, 1024));
  app.add_option("--background", o.background, "write the background mesh with its size fields (.vtu)");
  app.add_flag("--info", info_only, "print what was loaded (unit, bounding box, entity counts, free curves) and exit");
  app.add_flag("!--no-sew", o.load.sew, "do not sew faces that touch");
  app.add_flag("!--no-union", o.load.unite,
               "mesh each component where it lies: no repair of open components, no union of the closed ones");
  app.add_option("--sew-tolerance", o.load.sewing_tolerance_rel, "sewing tolerance relative to the bounding-box diagonal")
      ->capture_default_str()->check(positive);
  app.add_option("--deflection", o.tessellation.deflection_rel,
                 "background tessellation: chordal deflection relative to the bounding-box diagonal")
      ->capture_default_str()->check(positive);
  app.add_option("--angle", o.tessellation.angle_deg, "background tessellation: angular deflection in degrees")
      ->capture_default_str()->check(CLI::Range(0.1, 90.0));
  const auto* domain = "flow domain (faces marked 'farfield' and 'symmetry' in every output format)";
  std::string farfield = "none", symmetry = "none";
  app.add_option("--farfield", farfield, "outer boundary around the body: none, sphere or box")
      ->capture_default_str()->check(CLI::IsMember({"none", "sphere", "box"}))->group(domain);
  app.add_option("--farfield-size", o.load.domain.size,
                 "far-field radius (sphere) or half side (box), centred on the body (default 20 body diagonals)")
      ->check(positive)->group(domain);
  app.add_option("--farfield-h", o.load.domain.element_size, "element size on the far field (default a tenth of its size)")
      ->check(positive)->group(domain);
  auto* at = app.add_option("--symmetry-at", o.load.domain.symmetry_at,
                            "coordinate of the symmetry plane (default 0, or the body's side nearest to 0)")
                 ->check(finite_number)->group(domain);
  app.add_option("--symmetry", symmetry,
                 "half model: cut the body and the far field at the plane x, y or z = --symmetry-at, keep the "
                 "larger side")
      ->capture_default_str()->check(CLI::IsMember({"none", "x", "y", "z"}))->group(domain);
  auto* sizing = "sizing (paper 3.4; h_min/h_max default to 5e-4 and 0.05 of the bounding-box diagonal)";
  std::map<std::string, std::string> words;  // choice options: the word given
  for (const SizingOption& opt : sizing_options()) {
    CLI::Option* cli = nullptr;
    if (opt.on) {
      cli = app.add_flag("!" + opt.flag, o.sizing.*opt.on, opt.help);
    } else if (opt.number) {
      cli = app.add_option(opt.flag, o.sizing.*opt.number, opt.help);
      if (o.sizing.*opt.number != 0) cli->capture_default_str();
    } else {
      words[opt.key] = opt.get(o.sizing);
      cli = app.add_option(opt.flag, words[opt.key], opt.help)->capture_default_str()->check(CLI::IsMember(opt.choices));
    }
    if (opt.cli_lo < opt.cli_hi) cli->check(CLI::Range(opt.cli_lo, opt.cli_hi));
    cli->group(sizing);
  }
  app.add_option("--config", o.config,
                 "JSON config: the globals above and local phi_c, mu_d, beta, sizes per point/curve/face "
                 "(see examples/sizing.json); a flag given on the command line wins over the file")->group(sizing);
  std::string solver = "exact";
  app.add_option("--smoother", solver, "edge-gradation solver: exact (Dijkstra) or lpsolve (reference LP)")
      ->capture_default_str()->check(CLI::IsMember({"exact", "lpsolve"}))->group(sizing);
  app.add_flag("-q,--quiet", [&](int64_t) { o.verbose = false; }, "print nothing but errors");
  app.set_version_flag("--version", std::string("sizemesh ") + SIZEMESH_VERSION);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "sizemesh: error: " << e.what() << "\n";
    return kUsage;
  }
  o.edge_solver = solver == "lpsolve" ? EdgeSolver::LpSolve : EdgeSolver::Dijkstra;
  using FF = FlowDomainOptions::FarField;
  o.load.domain.farfield = farfield == "sphere" ? FF::Sphere : farfield == "box" ? FF::Box : FF::None;
  o.load.domain.symmetry_axis = symmetry == "none" ? -1 : symmetry[0] - 'x';
  o.load.domain.symmetry_at_given = at->count() > 0;
  for (const SizingOption& opt : sizing_options()) {
    if (opt.set) opt.set(o.sizing, words[opt.key]);
    if (app.count(opt.flag) > 0) o.sizing_from_cli.insert(opt.key);
  }
  try {
    if (info_only) {
      print_info(load_model(o.input, o.load), std::cout);
      return kOk;
    }
    return run(o);
  } catch (const Error& e) {
    std::cerr << "sizemesh: error: " << e.what() << "\n";
    return kError;
  } catch (const std::exception& e) {
    std::cerr << "sizemesh: error: " << e.what() << "\n";
    return kError;
  }
}
