#include "emulator/pacer.h"

#include <sys/resource.h>
#include <time.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace sonarloop::emulator {

// ---- pure rules ----

SimTime next_deadline(SimTime prev_deadline, SimTime period, SimTime now) {
  if (period <= 0) throw std::invalid_argument("next_deadline: period must be > 0 ns");
  const SimTime next = prev_deadline + period;
  if (next >= now) return next;
  // overrun: the first grid point at or after now (ceiling division; now > next > prev here)
  const SimTime ticks = (now - prev_deadline + period - 1) / period;
  return prev_deadline + ticks * period;
}

std::int64_t deadlines_skipped(SimTime prev_deadline, SimTime period, SimTime next) {
  if (period <= 0) throw std::invalid_argument("deadlines_skipped: period must be > 0 ns");
  return (next - prev_deadline) / period - 1;
}

PingWindow ping_window(SimTime send_time, SimTime next_send_time, SimTime now) {
  if (now < send_time) return PingWindow::kEarly;
  if (now < next_send_time) return PingWindow::kOpen;
  return PingWindow::kMissed;
}

// ---- the system clocks: the only clock reads of the emulator ----

namespace {
std::int64_t steady_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}
std::int64_t timeval_ns(const timeval& tv) {
  return static_cast<std::int64_t>(tv.tv_sec) * kNanosecondsPerSecond +
         static_cast<std::int64_t>(tv.tv_usec) * 1000;
}
}  // namespace

std::int64_t MonotonicClock::now_ns() const {
  return steady_ns();
}

std::int64_t MonotonicClock::utc_now_ns() const {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::int64_t MonotonicClock::process_cpu_ns() const {
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) != 0) return 0;
  return timeval_ns(u.ru_utime) + timeval_ns(u.ru_stime);
}

void MonotonicClock::sleep_until(std::int64_t deadline_ns) {
  if (deadline_ns <= 0) return;
  // libstdc++'s steady_clock is CLOCK_MONOTONIC: the same time base as now_ns()
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(deadline_ns / kNanosecondsPerSecond);
  ts.tv_nsec = static_cast<long>(deadline_ns % kNanosecondsPerSecond);
  // EINTR (a signal) returns early, as the interface allows: every caller rechecks its stop flag
  // and the time and sleeps again towards the same absolute deadline
  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
}

// ---- Wakeup ----

std::uint64_t Wakeup::generation() const {
  std::lock_guard<std::mutex> lock(mu_);
  return generation_;
}

void Wakeup::notify() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    ++generation_;
  }
  cv_.notify_all();
}

void Wakeup::wait_until(std::int64_t deadline_ns, std::uint64_t seen) {
  std::unique_lock<std::mutex> lock(mu_);
  if (deadline_ns == kForever) {
    cv_.wait(lock, [&] { return generation_ != seen; });
    return;
  }
  const std::chrono::steady_clock::time_point deadline{std::chrono::nanoseconds(deadline_ns)};
  cv_.wait_until(lock, deadline, [&] { return generation_ != seen; });
}

// ---- rate ----

Rate parse_rate(const std::string& text) {
  if (text == "realtime") return Rate{false, 1.0};
  if (text == "max") return Rate{true, 1.0};
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(begin, &end);
  const bool number = !text.empty() && end && *end == '\0' && errno == 0 && std::isfinite(x);
  if (!number || x < kMinRateFactor || x > kMaxRateFactor) {
    char allowed[160];
    std::snprintf(allowed, sizeof allowed,
                  "realtime, max, or a factor of real time from %g to %g (e.g. 2 = twice as fast)",
                  kMinRateFactor, kMaxRateFactor);
    throw std::invalid_argument("--rate '" + text + "' is not allowed: use " + allowed);
  }
  return Rate{false, x};
}

std::string to_string(const Rate& rate) {
  if (rate.max) return "max";
  if (rate.factor == 1.0) return "realtime";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%gx", rate.factor);
  return buf;
}

// ---- Pacer ----

Pacer::Pacer(Clock& clock, Rate rate) : clock_(clock), rate_(rate) {
  if (!rate_.max && !(rate_.factor >= kMinRateFactor && rate_.factor <= kMaxRateFactor)) {
    throw std::invalid_argument("Pacer: rate factor out of range");
  }
}

void Pacer::start() {
  start_at(clock_.now_ns());
}

void Pacer::start_at(std::int64_t wall_start_ns) {
  wall_start_ns_ = wall_start_ns;
  started_ = true;
}

std::int64_t Pacer::wall_of(SimTime t) const {
  if (rate_.max || rate_.factor == 1.0) return wall_start_ns_ + t;
  return wall_start_ns_ +
         static_cast<std::int64_t>(std::llround(static_cast<double>(t) / rate_.factor));
}

SimTime Pacer::sim_of(std::int64_t wall_ns) const {
  const std::int64_t dt = wall_ns - wall_start_ns_;
  if (rate_.max || rate_.factor == 1.0) return dt;
  return static_cast<SimTime>(std::llround(static_cast<double>(dt) * rate_.factor));
}

SimTime Pacer::sim_now() const {
  return sim_of(clock_.now_ns());
}

}  // namespace sonarloop::emulator
