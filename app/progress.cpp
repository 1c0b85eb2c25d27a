#include "app/progress.h"

#include <cstdio>
#include <unistd.h>

namespace sizemesh {

Progress::Progress(bool enabled, std::vector<std::pair<std::string, double>>& seconds)
    : enabled_(enabled), terminal_(isatty(STDERR_FILENO) == 1), seconds_(seconds) {}

void Progress::lap(const std::string& stage) {
  const double s = since(lap_);
  lap_ = Clock::now();
  seconds_.emplace_back(stage, s);
  if (!speaking()) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (counter_shown_ && terminal_) std::fputc('\n', stderr);
  counter_shown_ = false;
  std::fprintf(stderr, "sizemesh: %s done in %.2f s (%.1f s in all)\n", stage.c_str(), s, since(start_));
}

void Progress::faces(int done, int total) {
  if (!speaking() || total <= 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (terminal_) {
    if (done < total && since(last_print_) < 0.2) return;
    last_print_ = Clock::now();
    std::fprintf(stderr, "\rsizemesh: meshing faces %d / %d", done, total);
    counter_shown_ = true;
    return;
  }
  const int tenth = 10 * done / total;
  if (tenth <= last_tenth_) return;
  last_tenth_ = tenth;
  std::fprintf(stderr, "sizemesh: meshing faces %d / %d\n", done, total);
}

}  // namespace sizemesh
