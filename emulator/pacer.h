#pragma once
// Pacing of the real-time loop (docs/design.md, "Rules of the house"; docs/style.md habits 8-9).
//
// Everything the emulator schedules lives in simulation time (SimTime, ns since the mission
// start): ping k is emitted at k·ping_period, each NMEA 2000 PGN is sampled at multiples of its
// period. The pacer maps simulation time to wall time with absolute deadlines,
//   wall(t) = wall_start + t / rate,
// so lateness never accumulates: a late event does not shift the ones after it.
//
// This file holds
// - the pure scheduling rules (next_deadline, tested with a simulated clock, no sleeping);
// - Clock: the only interface through which the emulator reads a clock (the run loop, the render
//   workers and replay alike). MonotonicClock (pacer.cpp) is the one implementation that reads the
//   system clocks; every other component receives times as arguments or a Clock& / now function;
// - Wakeup: a sleep that another thread can cut short (a rendered ping became ready);
// - Pacer: the sim-time <-> wall-time mapping for --rate realtime | max | X.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <limits>
#include <mutex>
#include <string>

#include "sim/core/sim_time.h"

namespace sonarloop::emulator {

// ---- pure scheduling rules ----

// The deadline after `prev_deadline` on the grid prev_deadline + n·period (n >= 1), given that the
// current time is `now` (all in the same time base, ns):
// - on time (prev_deadline + period >= now): prev_deadline + period. Deadlines stay on the grid
//   whatever the lateness of each event, so they never drift;
// - after an overrun (prev_deadline + period < now: the next deadline has already passed): the
//   first grid point at or after `now`. The missed ticks are skipped, not made up in a burst
//   (resynchronisation), and deadlines_skipped() counts them.
// period must be > 0 (throws std::invalid_argument otherwise).
SimTime next_deadline(SimTime prev_deadline, SimTime period, SimTime now);

// Grid ticks skipped between prev_deadline and next (both on the grid of `period`): (next - prev)
// / period - 1, i.e. 0 when next_deadline() returned prev + period.
std::int64_t deadlines_skipped(SimTime prev_deadline, SimTime period, SimTime next);

// The window in which ping k may be sent: [send_time(k), send_time(k + 1)). Before it the ping
// waits; within it, it is sent as soon as it is rendered (late by now - send_time(k)); once the
// next ping's send time has come, ping k is dropped (counted) and the publisher moves on. This is
// the ping stream's resynchronisation: a stall never makes the publisher send a burst of old
// pings, and a ping that is ready in its window is never skipped.
enum class PingWindow { kEarly, kOpen, kMissed };
PingWindow ping_window(SimTime send_time, SimTime next_send_time, SimTime now);

// ---- clocks ----

// The clocks the emulator reads, all in ns. MonotonicClock reads the system; tests substitute a
// simulated clock (tests/emulator/simulated_clock.h).
class Clock {
 public:
  virtual ~Clock() = default;
  // Monotonic time (CLOCK_MONOTONIC): for deadlines, lateness and durations.
  virtual std::int64_t now_ns() const = 0;
  // UTC (CLOCK_REALTIME), ns since 1970-01-01: for the mission's epoch in real-time runs.
  virtual std::int64_t utc_now_ns() const = 0;
  // CPU time used by this process (user + system, getrusage), ns.
  virtual std::int64_t process_cpu_ns() const = 0;
  // Sleeps until monotonic time `deadline_ns` (absolute; returns at once if it has passed). May
  // return early when a signal arrives (so that Ctrl-C is seen at once): callers check their stop
  // flag and the time, and loop.
  virtual void sleep_until(std::int64_t deadline_ns) = 0;
};

// The system clocks (the only place in the emulator that reads a wall clock). sleep_until() is
// clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME): an absolute deadline, so a late wake-up never
// shifts the next one.
class MonotonicClock final : public Clock {
 public:
  std::int64_t now_ns() const override;
  std::int64_t utc_now_ns() const override;
  std::int64_t process_cpu_ns() const override;
  void sleep_until(std::int64_t deadline_ns) override;
};

// A wake-up signal: one thread sleeps until a deadline or until another thread calls notify(),
// whichever comes first. Usage: `auto seen = w.generation(); <check condition>;
// w.wait_until(deadline, seen)` (no notification between the check and the wait is lost).
class Wakeup {
 public:
  std::uint64_t generation() const;
  void notify();
  // Returns when generation() != seen, or at monotonic time deadline_ns (MonotonicClock's time
  // base: CLOCK_MONOTONIC), whichever comes first. deadline_ns = kForever waits for a notify.
  void wait_until(std::int64_t deadline_ns, std::uint64_t seen);

  static constexpr std::int64_t kForever = std::numeric_limits<std::int64_t>::max();

 private:
  mutable std::mutex mu_;
  std::condition_variable cv_;
  std::uint64_t generation_ = 0;
};

// ---- rate ----

// --rate: realtime (factor 1), X (X times real time, 0.01..1000), or max (as fast as the
// rendering allows: no sleeping, nothing dropped, no deadlines).
struct Rate {
  bool max = false;
  double factor = 1.0;  // simulated seconds per wall second (ignored when max)
};
inline constexpr double kMinRateFactor = 0.01;
inline constexpr double kMaxRateFactor = 1000.0;
// Parses "realtime", "max" or a number in [kMinRateFactor, kMaxRateFactor]. Throws
// std::invalid_argument naming the text and what is allowed.
Rate parse_rate(const std::string& text);
std::string to_string(const Rate& rate);  // "realtime", "max", "2x"

// Maps simulation time to wall (monotonic) time for a paced run, and says how late the loop is.
class Pacer {
 public:
  Pacer(Clock& clock, Rate rate);

  // Fixes wall time of t = 0 to the clock's current time (or `wall_start_ns` if given).
  void start();
  void start_at(std::int64_t wall_start_ns);
  bool started() const { return started_; }

  bool paced() const { return !rate_.max; }
  const Rate& rate() const { return rate_; }
  Clock& clock() const { return clock_; }
  std::int64_t wall_start_ns() const { return wall_start_ns_; }

  // Wall (monotonic) time at which simulation time t is due: wall_start + t / factor (exact
  // integer arithmetic at factor 1).
  std::int64_t wall_of(SimTime t) const;
  // Simulation time that corresponds to wall time `wall_ns` (the inverse of wall_of).
  SimTime sim_of(std::int64_t wall_ns) const;
  // sim_of(clock.now_ns()).
  SimTime sim_now() const;

 private:
  Clock& clock_;
  Rate rate_;
  bool started_ = false;
  std::int64_t wall_start_ns_ = 0;
};

}  // namespace sonarloop::emulator
