// sizemesh: automatic element sizing and surface meshing of CAD models.
#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

#include "src/batch.h"
#include "src/cli_options.h"
#include "src/info.h"
#include "src/pipeline.h"

int main(int argc, char** argv) {
  using namespace sizemesh;
  if (argc > 1 && std::string(argv[1]) == "batch") return run_batch(argc - 1, argv + 1);
  CLI::App app{
      "sizemesh: reads a STEP, IGES or BREP model and writes a triangular surface mesh whose element\n"
      "sizes follow the geometry (curvature, proximity, user sizes) with a bounded growth rate.\n"
      "Exit status: 0 success, 1 error (bad input or output), 2 bad command line, 3 partial mesh.\n"
      "Many files: sizemesh batch INPUTS... -o OUTDIR (see sizemesh batch --help)."};
  RunCommandLine cl;
  add_run_options(app, cl);
  app.set_version_flag("--version", std::string("sizemesh ") + SIZEMESH_VERSION);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "sizemesh: error: " << e.what() << "\n";
    return kUsage;
  }
  finish_run_options(app, cl);
  try {
    if (cl.info_only) {
      print_info(load_model(cl.options.input, cl.options.load), std::cout);
      return kOk;
    }
    return run(cl.options);
  } catch (const std::exception& e) {  // sizemesh::Error and anything a library throws
    std::cerr << "sizemesh: error: " << e.what() << "\n";
    return kError;
  }
}
