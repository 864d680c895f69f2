#include "tools/progress.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace sonarloop::tools {

Progress::Progress(std::string label, double total)
    : label_(std::move(label)),
      total_(total),
      start_(Clock::now()),
      last_draw_(start_),
      tty_(isatty(STDERR_FILENO) != 0) {}

Progress::~Progress() {
  finish();
}

void Progress::update(double done) {
  const auto now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < 1.0) return;
  const double since = std::chrono::duration<double>(now - last_draw_).count();
  if (drawn_ && since < (tty_ ? 0.1 : 5.0)) return;
  last_draw_ = now;
  drawn_ = true;
  const double frac = total_ > 0 ? std::clamp(done / total_, 0.0, 1.0) : 0.0;
  const double eta = frac > 0.01 ? elapsed * (1.0 - frac) / frac : 0.0;
  if (tty_) {
    const int width = 30;
    const int fill = static_cast<int>(frac * width + 0.5);
    std::fprintf(stderr, "\r%s [%.*s%*s] %3.0f%%  %.1f s, %.0f s left ", label_.c_str(), fill,
                 "##############################", width - fill, "", 100.0 * frac, elapsed, eta);
  } else {
    std::fprintf(stderr, "%s: %.0f%% after %.1f s\n", label_.c_str(), 100.0 * frac, elapsed);
  }
  std::fflush(stderr);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (drawn_ && tty_) {
    std::fprintf(stderr, "\r%s done in %.1f s%40s\n", label_.c_str(), seconds_since(start_), "");
  }
}

double peak_rss_mib() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_maxrss) / 1024.0;  // Linux reports KiB
}

}  // namespace sonarloop::tools
