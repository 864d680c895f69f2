// Each ping at the pose of its own time: the per-part sample track (interpolation, heading the
// short way round, extrapolation and its bound) and the stamp-to-clock placement.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "emulator/pose_history.h"
#include "tests/emulator/time_units.h"

using namespace sonarloop::emulator;
using sonarloop::testing::kMs;

namespace {
constexpr std::int64_t kNoLimit = 1'000'000 * kMs;
}  // namespace

TEST_CASE("pose history: interpolates between the samples around the time") {
  PartTrack<2> track;
  REQUIRE_FALSE(track.value_at(0, kNoLimit));
  CHECK(track.add(100 * kMs, {0.0, 10.0}));
  CHECK(track.add(200 * kMs, {0.2, 10.0}));
  CHECK(track.add(300 * kMs, {0.4, 12.0}));

  const auto mid = track.value_at(250 * kMs, kNoLimit);
  REQUIRE(mid);
  CHECK(mid->v[0] == Approx(0.3));
  CHECK(mid->v[1] == Approx(11.0));
  CHECK_FALSE(mid->extrapolated);
  // before the first: the first
  const auto early = track.value_at(0, kNoLimit);
  CHECK(early->v[0] == 0.0);
  CHECK_FALSE(early->extrapolated);
  // exactly on a sample
  CHECK(track.value_at(200 * kMs, kNoLimit)->v[0] == Approx(0.2));
}

TEST_CASE("pose history: after the last sample, extrapolated at the last rate, bounded") {
  PartTrack<2> track;
  track.add(0, {0.0, 0.0});
  // a single sample is held
  const auto held = track.value_at(50 * kMs, kNoLimit);
  CHECK(held->v[0] == 0.0);
  CHECK(held->extrapolated);
  track.add(100 * kMs, {0.2, -0.1});  // 2 m/s north, 1 m/s west
  const auto ahead = track.value_at(150 * kMs, kNoLimit);
  CHECK(ahead->v[0] == Approx(0.3));
  CHECK(ahead->v[1] == Approx(-0.15));
  CHECK(ahead->extrapolated);
  // no further than the bound beyond the last sample
  const auto far = track.value_at(10'000 * kMs, 500 * kMs);
  CHECK(far->v[0] == Approx(1.2));
}

TEST_CASE("pose history: a heading crossing north turns the short way round") {
  PartTrack<1> heading(true);
  const double two_pi = 2.0 * std::numbers::pi;
  heading.add(0, {two_pi - 0.1});
  heading.add(100 * kMs, {0.1});
  const double mid = heading.value_at(50 * kMs, kNoLimit)->v[0];
  CHECK((mid < 1e-9 || mid > two_pi - 1e-9));  // north, not south
  CHECK(heading.value_at(75 * kMs, kNoLimit)->v[0] == Approx(0.05));
  // extrapolated turn rate: 0.2 rad per 100 ms
  CHECK(heading.value_at(150 * kMs, kNoLimit)->v[0] == Approx(0.2));
  CHECK(shortest_turn_rad(0.1, two_pi - 0.1) == Approx(-0.2));
}

TEST_CASE("pose history: old samples dropped, same time replaced, ring bounded") {
  PartTrack<1> track;
  CHECK(track.add(100 * kMs, {1.0}));
  CHECK_FALSE(track.add(50 * kMs, {9.0}));  // older than the newest
  CHECK(track.add(100 * kMs, {2.0}));       // same time: replaces
  CHECK(track.size() == 1);
  CHECK(track.newest().v[0] == 2.0);
  for (int i = 1; i <= 3 * kPoseHistorySamples; ++i)
    track.add((100 + i * 10) * kMs, {static_cast<double>(i)});
  CHECK(track.size() == kPoseHistorySamples);
  // interpolation still right across the ring's wrap
  const std::int64_t last = (100 + 3 * kPoseHistorySamples * 10) * kMs;
  CHECK(track.value_at(last - 5 * kMs, kNoLimit)->v[0] == Approx(3.0 * kPoseHistorySamples - 0.5));
  track.clear();
  CHECK(track.empty());
}

TEST_CASE("pose history: stamps placed by the smallest delay, jitter does not move them") {
  StampClock clock;
  const std::int64_t offset = 5'000 * kMs;  // the two clocks differ by 5 s
  // within 20 us: the filter relaxes by 100 ppm of the time between arrivals
  auto near = [](std::int64_t a, std::int64_t b) { return std::llabs(a - b) < 20'000; };
  // the first message is 30 ms late, the others 1 ms; one more 20 ms late
  CHECK(clock.place(0, offset + 30 * kMs) == offset + 30 * kMs);
  CHECK(near(clock.place(100 * kMs, offset + 101 * kMs), offset + 101 * kMs));
  CHECK(near(clock.place(200 * kMs, offset + 220 * kMs), offset + 201 * kMs));
  CHECK(near(clock.place(300 * kMs, offset + 301 * kMs), offset + 301 * kMs));
  // a sample is never placed after its own arrival
  CHECK(clock.place(400 * kMs, offset + 390 * kMs) == offset + 390 * kMs);
}
