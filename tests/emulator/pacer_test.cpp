// The pacing rules with a simulated clock: no sleeping, no wall clock.
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <thread>

#include "common/rng.h"
#include "emulator/pacer.h"
#include "tests/emulator/simulated_clock.h"

using namespace sonarloop;
using namespace sonarloop::emulator;
using sonarloop::testing::SimulatedClock;

namespace {

// The simulated clock's time at the start of each test: any time well away from 0 will do.
constexpr std::int64_t kPacerClockStartNs = 5'000'000'000;

}  // namespace

TEST_CASE("next_deadline: on time, the next grid point; late but within a period, still it") {
  const SimTime p = 100;
  CHECK(next_deadline(0, p, 0) == 100);
  CHECK(next_deadline(0, p, 37) == 100);
  CHECK(next_deadline(0, p, 99) == 100);
  CHECK(next_deadline(0, p, 100) == 100);  // due exactly now: not missed
  CHECK(deadlines_skipped(0, p, 100) == 0);
  CHECK(next_deadline(1000, p, 1000) == 1100);
  CHECK_THROWS_AS(next_deadline(0, 0, 0), std::invalid_argument);
}

TEST_CASE("next_deadline: after an overrun it resyncs to the first grid point at or after now") {
  const SimTime p = 100;
  CHECK(next_deadline(0, p, 101) == 200);
  CHECK(deadlines_skipped(0, p, 200) == 1);
  CHECK(next_deadline(0, p, 250) == 300);
  CHECK(deadlines_skipped(0, p, 300) == 2);
  CHECK(next_deadline(0, p, 300) == 300);
  CHECK(next_deadline(500, p, 12'345) == 12'400);  // stays on the grid 500 + n·100
  CHECK(deadlines_skipped(500, p, 12'400) == 118);
}

TEST_CASE("next_deadline never accumulates drift: 100000 events with random lateness") {
  // a loop that handles each event up to 0.9 period late: every deadline is exactly k·period
  const SimTime period = 66'666'667;  // not a divisor of anything round
  SimulatedClock clock(kPacerClockStartNs);
  const std::int64_t start = clock.now_ns();
  sonarloop::Rng rng(42);
  SimTime deadline = 0;
  for (int k = 1; k <= 100'000; ++k) {
    const SimTime lateness = static_cast<SimTime>(rng.uniform() * 0.9 * period);
    clock.sleep_until(start + deadline);
    clock.advance(lateness);  // handling the event takes this long
    const SimTime next = next_deadline(deadline, period, clock.now_ns() - start);
    REQUIRE(next == deadline + period);
    deadline = next;
  }
  CHECK(deadline == 100'000 * period);
  // and the clock is never further than one event's handling past the last deadline
  CHECK(clock.now_ns() - start - (deadline - period) < period);
}

TEST_CASE("next_deadline resyncs after overruns and then runs on time again, on the same grid") {
  const SimTime period = 10'000'000;
  SimulatedClock clock(kPacerClockStartNs);
  const std::int64_t start = clock.now_ns();
  SimTime deadline = 0;
  std::int64_t skipped = 0, handled = 0;
  for (int i = 0; i < 1000; ++i) {
    clock.sleep_until(start + deadline);
    ++handled;
    // every 100th event stalls for 3.5 periods (a page fault storm, a descheduled thread)
    clock.advance(i % 100 == 99 ? 35 * period / 10 : period / 10);
    const SimTime next = next_deadline(deadline, period, clock.now_ns() - start);
    skipped += deadlines_skipped(deadline, period, next);
    REQUIRE(next % period == 0);                         // on the grid
    REQUIRE(next >= clock.now_ns() - start);             // never in the past: no burst
    REQUIRE(next - (clock.now_ns() - start) <= period);  // nor needlessly late
    deadline = next;
  }
  // 10 stalls of 3.5 periods: each skips the 3 ticks that passed during it
  CHECK(skipped == 30);
  CHECK(deadline == (handled + skipped) * period);
}

TEST_CASE("ping_window: wait, send, drop") {
  CHECK(ping_window(100, 200, 99) == PingWindow::kEarly);
  CHECK(ping_window(100, 200, 100) == PingWindow::kOpen);
  CHECK(ping_window(100, 200, 199) == PingWindow::kOpen);
  CHECK(ping_window(100, 200, 200) == PingWindow::kMissed);
}

TEST_CASE("Pacer maps simulation time to wall time with absolute deadlines") {
  SimulatedClock clock(kPacerClockStartNs);
  Pacer realtime(clock, parse_rate("realtime"));
  realtime.start();
  const std::int64_t w0 = clock.now_ns();
  CHECK(realtime.paced());
  CHECK(realtime.wall_of(0) == w0);
  CHECK(realtime.wall_of(1'234'567'891) == w0 + 1'234'567'891);
  clock.advance(777);
  CHECK(realtime.sim_now() == 777);

  Pacer fast(clock, parse_rate("4"));
  fast.start_at(1000);
  CHECK(fast.wall_of(4'000'000'000) == 1000 + 1'000'000'000);
  CHECK(fast.sim_of(1000 + 250) == 1000);
  // the mapping has no drift: deadline k is k·period/4 after the start, whatever k
  const SimTime period = 66'666'667;
  CHECK(fast.wall_of(3'000'000 * period) - 1000 == 750'000 * period);

  Pacer max(clock, parse_rate("max"));
  CHECK_FALSE(max.paced());
}

TEST_CASE("parse_rate: realtime, max and factors; anything else is an error naming it") {
  CHECK(parse_rate("realtime").factor == 1.0);
  CHECK(parse_rate("max").max);
  CHECK(parse_rate("2.5").factor == 2.5);
  CHECK(parse_rate("0.5").factor == 0.5);
  CHECK(to_string(parse_rate("2")) == "2x");
  CHECK(to_string(parse_rate("realtime")) == "realtime");
  for (const char* bad : {"", "fast", "0", "-1", "1e6", "nan", "2x", "inf"}) {
    INFO(bad);
    try {
      parse_rate(bad);
      FAIL("accepted");
    } catch (const std::invalid_argument& e) {
      CHECK(std::string(e.what()).find("realtime, max") != std::string::npos);
    }
  }
}

TEST_CASE("Wakeup: a notify ends a wait early; a deadline ends it otherwise, not before") {
  Wakeup w;
  const auto seen = w.generation();
  w.notify();
  w.wait_until(Wakeup::kForever, seen);  // returns: generation changed
  CHECK(w.generation() == seen + 1);
  // another thread's notify ends a wait without a deadline
  const auto g = w.generation();
  std::thread notifier([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    w.notify();
  });
  w.wait_until(Wakeup::kForever, g);
  CHECK(w.generation() == g + 1);
  notifier.join();
  // no notify: the wait ends at its deadline (MonotonicClock's time base), not earlier
  MonotonicClock clock;
  const auto g2 = w.generation();
  const std::int64_t deadline = clock.now_ns() + 20'000'000;
  w.wait_until(deadline, g2);
  CHECK(clock.now_ns() >= deadline);
  CHECK(w.generation() == g2);
  // a deadline already passed returns without a notify
  w.wait_until(clock.now_ns() - 1, g2);
  CHECK(w.generation() == g2);
}
