// sizemesh: automatic element sizing and surface meshing of CAD models.
#include <CLI/CLI.hpp>
#include <malloc.h>

#include <iostream>
#include <string>

#include "app/batch.h"
#include "app/cli_options.h"
#include "app/info.h"
#include "app/pipeline.h"
#include "app/watchdog.h"

namespace {

// OCCT's Boolean operations project points onto B-spline surfaces through
// Extrema_GenExtPS, which allocates and frees grids of several hundred
// kilobytes per projection. glibc serves blocks that large with mmap, so each
// one costs fresh pages (page faults and zeroing: half the time of the F-16's
// union, by perf). Blocks up to 64 MB stay on the heap instead, and up to
// 256 MB of free heap is kept rather than returned at once.
void keep_large_blocks_on_heap() {
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  mallopt(M_TOP_PAD, 64 << 20);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace sizemesh;
  keep_large_blocks_on_heap();
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
    // The repair before the union has no budget of its own (a component's
    // sewing trials take seconds on a loaded machine): the net is wide.
    cl.options.preparation_grace = 60;
    if (cl.info_only) {
      cl.options.load.describe_only = true;
      const CadFile cad = read_cad(cl.options.input, cl.options.load);
      const auto hard_stop = preparation_hard_stop(cad, cl.options);
      print_info(prepare_model(cad, cl.options.load), std::cout);
      return kOk;
    }
    return run(cl.options);
  } catch (const std::exception& e) {  // sizemesh::Error and anything a library throws
    std::cerr << "sizemesh: error: " << e.what() << "\n";
    return kError;
  }
}
