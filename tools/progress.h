#pragma once
// A progress bar on stderr for long jobs: silent for the first second, then a bar redrawn at
// most 10 times a second on a terminal, or a plain line every 5 s when stderr is a file.
// Tools may read the wall clock (docs/design.md: only sim/ must not).
#include <chrono>
#include <string>

namespace sonarloop::tools {

class Progress {
 public:
  Progress(std::string label, double total);
  ~Progress();
  void update(double done);
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  std::string label_;
  double total_;
  Clock::time_point start_;
  Clock::time_point last_draw_;
  bool tty_;
  bool drawn_ = false;
  bool finished_ = false;
};

// Seconds since `start` as a double.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Peak resident set size of this process so far, in MiB.
double peak_rss_mib();

}  // namespace sonarloop::tools
