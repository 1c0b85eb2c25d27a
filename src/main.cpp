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
  app.add_option("-o,--output", o.output, "output mesh (.vtu)");
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
  app.add_flag("-q,--quiet", [&](int64_t) { o.verbose = false; }, "print nothing but errors");
  app.set_version_flag("--version", std::string("sizemesh ") + SIZEMESH_VERSION);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "sizemesh: error: " << e.what() << "\n";
    return kUsage;
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
