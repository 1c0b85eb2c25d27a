// sizemesh: automatic element sizing and surface meshing of CAD models.
#include <CLI/CLI.hpp>

#include <iostream>

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
  app.add_option("--sew-tolerance", o.load.sewing_tolerance_rel, "sewing tolerance relative to the bounding-box diagonal")
      ->capture_default_str()->check(positive);
  app.add_option("--deflection", o.tessellation.deflection_rel,
                 "background tessellation: chordal deflection relative to the bounding-box diagonal")
      ->capture_default_str()->check(positive);
  app.add_option("--angle", o.tessellation.angle_deg, "background tessellation: angular deflection in degrees")
      ->capture_default_str()->check(CLI::Range(0.1, 90.0));
  auto* sizing = "sizing (paper 3.4; h_min/h_max default to 1e-3 and 0.05 of the bounding-box diagonal)";
  app.add_option("--phi-c", o.sizing.phi_c_deg, "curvature: central angle per element, degrees, in (0, 180)")
      ->capture_default_str()->group(sizing);
  app.add_option("--mu-d", o.sizing.mu_d, "proximity: elements across a thin region, > 0")
      ->capture_default_str()->group(sizing);
  app.add_option("--beta", o.sizing.beta, "gradation: largest size ratio between neighbouring elements, >= 1")
      ->capture_default_str()->group(sizing);
  app.add_option("--h-min", o.sizing.h_min, "smallest element size (model units)")->group(sizing);
  app.add_option("--h-max", o.sizing.h_max, "largest element size (model units)")->group(sizing);
  app.add_option("--deviation", o.sizing.deviation,
                 "curvature: largest chord height of an element edge off the surface (model units; 0: no bound)")
      ->group(sizing);
  app.add_flag("!--no-proximity", o.sizing.proximity,
               "size from curvature (and user sizes) alone: no face width, curve length or gap sizes")
      ->group(sizing);
  app.add_flag("!--no-gaps", o.sizing.local_proximity,
               "do not refine thin gaps between faces (plates, blunt trailing edges, part gaps)")->group(sizing);
  app.add_flag("!--no-refine-background", o.sizing.refine_background,
               "keep the tessellation as the background mesh, even where its edges are too long for sizes to grow")
      ->group(sizing);
  app.add_option("--max-triangles", o.sizing.max_triangles,
                 "refuse, before meshing, a size map that asks for more triangles (an estimate from the map)")
      ->capture_default_str()->check(CLI::Range(1.0, 1e15))->group(sizing);
  app.add_option("--config", o.config,
                 "JSON config: the globals above and local phi_c, mu_d, beta, sizes per point/curve/face "
                 "(see examples/sizing.json)")->group(sizing);
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
