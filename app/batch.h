// `sizemesh batch`: many CAD files, each meshed by the sizemesh command in a
// process of its own (a crash, a hang or a memory blow-up in one file cannot
// take the others down), a few at a time, with OUTDIR/summary.csv holding one
// row per file: status, triangles, wall time, peak memory, bad triangles and
// failed faces.
#pragma once

namespace sizemesh {

// argv[0] is "batch". Returns the exit status: 0 when every file meshed, 3
// when some failed or are partial, 1 when nothing could start (no input, no
// output folder), 2 for a bad command line, 128 + the signal when stopped by
// SIGINT or SIGTERM (the summary is written all the same).
int run_batch(int argc, char** argv);

}  // namespace sizemesh
