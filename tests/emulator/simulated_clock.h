#pragma once
// The simulated clock the emulator's tests use in place of emulator::MonotonicClock: time moves
// only when told to (advance) or when something sleeps (sleep_until jumps to the deadline), so
// tests check deadlines exactly, without sleeping and without a wall clock. The pacer, render
// queue and replay tests share it, so that they all test against the one Clock interface.
//
// Thread-safe: the render-queue tests advance it from worker threads while the main thread reads.
#include <atomic>
#include <cstdint>

#include "emulator/pacer.h"

namespace sonarloop::testing {

class SimulatedClock final : public emulator::Clock {
 public:
  // UTC of monotonic time 0 (2023-11-14T22:13:20Z): any fixed, plausible epoch will do.
  static constexpr std::int64_t kUtcEpochNs = 1'700'000'000'000'000'000;

  explicit SimulatedClock(std::int64_t start_ns = 0) : now_(start_ns) {}

  std::int64_t now_ns() const override { return now_.load(); }
  std::int64_t utc_now_ns() const override { return kUtcEpochNs + now_.load(); }
  std::int64_t process_cpu_ns() const override { return 0; }
  // Jumps to the deadline (never back), as if the sleep had lasted exactly until then.
  void sleep_until(std::int64_t deadline_ns) override {
    std::int64_t now = now_.load();
    while (deadline_ns > now && !now_.compare_exchange_weak(now, deadline_ns)) {
    }
  }

  void advance(std::int64_t ns) { now_.fetch_add(ns); }

 private:
  std::atomic<std::int64_t> now_;
};

}  // namespace sonarloop::testing
