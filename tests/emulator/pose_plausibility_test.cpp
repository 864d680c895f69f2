// Implausible external poses (emulator/pose_source.h, "Plausibility"; pose_merger.h): absurd
// depth, altitude and attitude, position jumps, time stamps going back or ahead, refused,
// counted and warned; the limits from a scene.
#include "emulator/pose_source.h"

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "drivers/can/socketcan.h"
#include "drivers/can/socketcand_client.h"
#include "drivers/can/socketcand_server.h"
#include "drivers/n2k/messages.h"
#include "drivers/net/udp_receiver.h"
#include "drivers/net/udp_sender.h"
#include "drivers/pose/pose_message.h"
#include "tests/emulator/pose_source_support.h"
#include "tests/support/skip.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;
using namespace sonarloop::emulator;
using namespace sonarloop::emulator::pose_test;
using Catch::Matchers::Contains;

// ---------------------------------------------------------------------------------------------
// implausible poses (docs: pose_source.h "Plausibility")

namespace {

// A UDP source with the limits of a 50 m deep scene whose warnings are collected.
struct CheckedUdpSource {
  InjectedClock clock;
  std::mutex mu;
  std::vector<std::string> warnings;
  std::unique_ptr<UdpPoseSource> source;
  std::unique_ptr<net::UdpSender> tx;

  explicit CheckedUdpSource(const LocalTangentPlane& ltp) {
    PoseSourceOptions options;
    options.limits.max_depth_m = 50.0;
    options.limits.max_altitude_m = 51.0;
    options.on_warning = [this](const std::string& w) {
      std::lock_guard lock(mu);
      warnings.push_back(w);
    };
    source =
        std::make_unique<UdpPoseSource>(net::HostPort{"127.0.0.1", 0}, ltp, clock.fn(), options);
    tx = std::make_unique<net::UdpSender>(net::HostPort{"127.0.0.1", source->bound_port()});
  }
  // Sends `m` and waits until it is accepted or rejected.
  void deliver(const PoseMessage& m) {
    const auto before = source->stats();
    send(*tx, m);
    REQUIRE(wait_until([&] {
      const auto s = source->stats();
      return s.updates + s.rejected > before.updates + before.rejected;
    }));
  }
  std::vector<std::string> warnings_now() {
    std::lock_guard lock(mu);
    return warnings;
  }
};

// message(seq) without its time stamp: samples placed at their arrival (the injected clock)
PoseMessage unstamped(std::uint32_t seq) {
  PoseMessage m = message(seq);
  m.time_unix_ns = 0;
  return m;
}

constexpr std::int64_t kSecond = 1'000'000'000;

}  // namespace

TEST_CASE("pose source udp: absurd depth, altitude and attitude are rejected, counted, warned") {
  const LocalTangentPlane ltp(kOrigin);
  CheckedUdpSource c(ltp);
  c.clock.value = 1 * kSecond;
  c.deliver(unstamped(1));
  REQUIRE(c.source->stats().updates == 1);

  // each one absurd in one way; the clock does not move: one warning line for all
  std::vector<std::pair<std::function<void(PoseMessage&)>, std::string>> absurd = {
      {[](PoseMessage& m) { m.depth_m = -5.0; }, "above the sea surface"},
      {[](PoseMessage& m) { m.depth_m = 1e6; }, "below the scene's deepest seabed (50.0 m)"},
      {[](PoseMessage& m) { m.altitude_m = -0.5; }, "below the seabed"},
      {[](PoseMessage& m) { m.altitude_m = 4000.0; }, "more than the scene's water column"},
      {[](PoseMessage& m) { m.pitch_rad = 1.6; }, "beyond +-90"},
      {[](PoseMessage& m) { m.roll_rad = -std::numbers::pi; }, "beyond +-90"},
  };
  std::uint32_t seq = 2;
  for (const auto& [edit, reason] : absurd) {
    PoseMessage m = unstamped(seq++);
    edit(m);
    c.deliver(m);
    CHECK_THAT(c.source->stats().last_error, Contains(reason));
  }
  auto s = c.source->stats();
  CHECK(s.rejected == absurd.size());
  CHECK(s.updates == 1);
  CHECK(s.malformed == 0);
  CHECK(s.lost == 0);  // rejected messages were received, not lost
  // nothing of them reached the pose: its time and depth are the first message's
  CHECK(c.source->latest()->received_ns == 1 * kSecond);
  CHECK(c.source->latest()->pose.position_W.z() == 35.5);
  auto w = c.warnings_now();
  REQUIRE(w.size() == 1);
  CHECK_THAT(w[0], Contains("udp pose on 127.0.0.1:") &&
                       Contains("implausible pose rejected: pose message 2: depth -5 m"));

  // a second later the next rejection is warned about again, with the count in between
  c.clock.value = 2 * kSecond;
  PoseMessage deep = unstamped(seq++);
  deep.depth_m = 60.0;
  c.deliver(deep);
  w = c.warnings_now();
  REQUIRE(w.size() == 2);
  CHECK_THAT(w[1], Contains("depth 60 m") && Contains("(and 5 more since the last such warning)"));
  CHECK_THAT(c.source->describe(), Contains("7 rejected as implausible"));

  // NaN is "not available" (not absurd): accepted, the part then unknown; a surfaced vehicle
  // 0.5 m "above" the surface in a wave is the surface
  PoseMessage partial = unstamped(seq++);
  partial.depth_m = kNaN;
  partial.pitch_rad = kNaN;
  c.deliver(partial);
  PoseMessage surfaced = unstamped(seq++);
  surfaced.depth_m = -0.5;
  c.deliver(surfaced);
  s = c.source->stats();
  CHECK(s.updates == 3);
  CHECK(s.rejected == 7);
  CHECK(c.source->latest()->pose.position_W.z() == -0.5);
}

TEST_CASE("pose source udp: a position jump faster than a vehicle is rejected until it persists") {
  const LocalTangentPlane ltp(kOrigin);
  CheckedUdpSource c(ltp);
  auto at = [&](std::uint32_t seq, double north_m) {
    PoseMessage m = unstamped(seq);
    const GeoPoint g = ltp.to_geodetic(north_m, 0.0);
    m.latitude_deg = g.latitude_deg;
    m.longitude_deg = g.longitude_deg;
    return m;
  };
  c.clock.value = 10 * kSecond;
  c.deliver(at(1, 0.0));
  // 2 m in 0.1 s (20 m/s, the vehicle speed limit, plus 5 m for a navigation fix): plausible
  c.clock.value += kSecond / 10;
  c.deliver(at(2, 2.0));
  REQUIRE(c.source->stats().updates == 2);
  // 1 km in 0.1 s: a glitch, rejected; the pose stays where it was
  c.clock.value += kSecond / 10;
  c.deliver(at(3, 1000.0));
  CHECK(c.source->stats().rejected == 1);
  CHECK_THAT(c.source->stats().last_error, Contains("position jumped 998 m in 0.100 s"));
  CHECK(c.source->latest()->pose.position_W.x() == Approx(2.0).margin(1e-6));
  // the next fix is back on the track: accepted, and the rejection count starts again
  c.clock.value += kSecond / 10;
  c.deliver(at(4, 2.5));
  CHECK(c.source->stats().updates == 3);
  // a real relocation: rejected reanchor_after - 1 times, then taken as the new position
  const int n = PoseLimits{}.reanchor_after;
  for (int i = 0; i < n; ++i) {
    c.clock.value += kSecond / 10;
    c.deliver(at(static_cast<std::uint32_t>(5 + i), 500.0 + 0.2 * i));
  }
  const auto s = c.source->stats();
  CHECK(s.rejected == 1 + static_cast<std::uint64_t>(n - 1));
  CHECK(s.reanchors == 1);
  CHECK(c.source->latest()->pose.position_W.x() == Approx(500.0 + 0.2 * (n - 1)).margin(1e-6));
  // no interpolation across the jump: just after it, the new position (not a blend with 2.5 m)
  const auto p = c.source->pose_at(c.clock.value - kSecond / 20, kSecond);
  CHECK(p->pose.position_W.x() == Approx(500.0 + 0.2 * (n - 1)).margin(1e-6));
  const auto w = c.warnings_now();
  REQUIRE(!w.empty());
  CHECK_THAT(w.back(), Contains("accepted as the new position after 5 such fixes in a row"));
}

TEST_CASE("pose source udp: time stamps going back or jumping ahead are rejected") {
  const LocalTangentPlane ltp(kOrigin);
  CheckedUdpSource c(ltp);
  const std::int64_t stamp0 = 1'767'225'600'000'000'000;
  auto stamped = [&](std::uint32_t seq, std::int64_t stamp, double north_m) {
    PoseMessage m = message(seq);
    m.time_unix_ns = stamp;
    const GeoPoint g = ltp.to_geodetic(north_m, 0.0);
    m.latitude_deg = g.latitude_deg;
    m.longitude_deg = g.longitude_deg;
    return m;
  };
  c.clock.value = 100 * kSecond;
  c.deliver(stamped(1, stamp0, 0.0));
  c.clock.value += kSecond / 10;
  c.deliver(stamped(2, stamp0 + kSecond / 10, 0.2));
  // 10 s back in time (sequence going on): rejected
  c.clock.value += kSecond / 10;
  c.deliver(stamped(3, stamp0 - 10 * kSecond, 0.4));
  CHECK_THAT(c.source->stats().last_error, Contains("time stamp went back 10.1 s"));
  // an hour ahead in 0.2 s of arrivals: rejected. (Before this check one such stamp moved the
  // stamp-to-clock offset by an hour, and every later sample was placed an hour in the past
  // and dropped from the history: the pose froze while the source looked fresh.)
  c.clock.value += kSecond / 10;
  c.deliver(stamped(4, stamp0 + 3600 * kSecond, 0.6));
  CHECK_THAT(c.source->stats().last_error, Contains("time stamp jumped ahead 3599.9 s"));
  CHECK(c.source->stats().rejected == 2);
  // the sender's next sample is placed on the clock and read back from the history
  c.clock.value += kSecond / 10;
  c.deliver(stamped(5, stamp0 + 4 * kSecond / 10, 0.8));
  CHECK(c.source->stats().updates == 3);
  const auto p = c.source->pose_at(c.clock.value, 0);
  REQUIRE(p);
  CHECK(p->pose.position_W.x() == Approx(0.8).margin(1e-6));
  // a clock really stepped (by an hour) is followed after reanchor_after messages
  const int n = PoseLimits{}.reanchor_after;
  for (int i = 0; i < n; ++i) {
    c.clock.value += kSecond / 10;
    c.deliver(stamped(static_cast<std::uint32_t>(6 + i), stamp0 + (3600 + i) * kSecond, 1.0));
  }
  CHECK(c.source->stats().reanchors == 1);
  CHECK(c.source->stats().rejected == 2 + static_cast<std::uint64_t>(n - 1));
  CHECK(c.source->latest()->received_ns == c.clock.value);
}

TEST_CASE("pose source: pose_limits_for_scene bounds depth by the scene's deepest seabed") {
  scene::SceneDesc sc;
  sc.water.depth_m = 30.0;
  sc.seabed.origin_m = Vec2(-50.0, -50.0);
  sc.seabed.extent_m = Vec2(100.0, 100.0);
  sc.seabed.elevation.slope = Vec2(0.01, 0.0);  // rising 1 cm per metre north
  sc.seabed.elevation.rms_m = 0.5;
  const PoseLimits l = pose_limits_for_scene(sc);
  // deepest at the south edge: 30 + 0.01 x 50 + 6 x 0.5
  CHECK(l.max_depth_m == Approx(33.5));
  CHECK(l.max_altitude_m == Approx(34.5));
  CHECK(l.max_speed_m_s == 20.0);  // the vehicle's speed limit (vehicle_desc.cpp)
  CHECK(l.max_pitch_rad == Approx(std::numbers::pi / 2));
}

TEST_CASE("pose merger: implausible NMEA 2000 attitude, depth and position jumps are rejected") {
  const LocalTangentPlane ltp(kOrigin);
  std::int64_t now = 0;
  PoseLimits limits;
  limits.max_depth_m = 30.0;
  limits.max_altitude_m = 31.0;
  std::vector<std::string> warnings;
  PoseMerger merger(
      ltp, [&] { return now; }, limits, [&](const std::string& w) { warnings.push_back(w); });
  n2k::Attitude a;
  a.pitch_rad = 0.1;
  a.roll_rad = 1.7;  // beyond 90 degrees
  CHECK_FALSE(merger.merge_n2k(n2k::encode(a, 1)));
  n2k::WaterDepth w;
  w.depth_m = 5.0;
  w.offset_m = 31.5;  // deeper than the seabed
  CHECK_FALSE(merger.merge_n2k(n2k::encode(w, 1)));
  CHECK(merger.merge_n2k(n2k::encode(n2k::PositionRapidUpdate{59.9, 10.75}, 1)));
  now += kSecond;
  CHECK_FALSE(merger.merge_n2k(n2k::encode(n2k::PositionRapidUpdate{59.91, 10.75}, 1)));  // 1.1 km
  const auto s = merger.stats();
  CHECK(s.rejected == 3);
  CHECK(s.updates == 1);
  CHECK_THAT(s.last_error, Contains("129025 Position: position jumped"));
  REQUIRE(warnings.size() == 2);  // the third within a second of the first: counted, not said
  CHECK_THAT(warnings[0], Contains("127257 Attitude: pitch 5.7 / roll 97.4 degrees"));
  CHECK_THAT(warnings[1], Contains("(and 1 more since the last such warning)"));
}

TEST_CASE("pose source udp: a sender alternating two clocks is said once a second, not each time") {
  // groups of reanchor_after messages on clocks an hour apart, at 100 Hz for 10 s: each group
  // is rejected but for its last message, which re-anchors (200 re-anchorings, 800 rejections)
  const LocalTangentPlane ltp(kOrigin);
  CheckedUdpSource c(ltp);
  const std::int64_t stamp0 = 1'767'225'600'000'000'000;
  const int n = PoseLimits{}.reanchor_after;
  c.clock.value = 100 * kSecond;
  for (std::uint32_t k = 0; k < 1000; ++k) {
    c.clock.value += kSecond / 100;
    PoseMessage m = message(k + 1);
    const bool second_clock = (k / static_cast<std::uint32_t>(n)) % 2 == 1;
    m.time_unix_ns = stamp0 + static_cast<std::int64_t>(k) * (kSecond / 100) +
                     (second_clock ? 3600 * kSecond : 0);
    c.deliver(m);
  }
  const auto s = c.source->stats();
  CHECK(s.reanchors >= 150);
  CHECK(s.rejected >= 600);
  // at most one line of each kind a second (11 s of the injected clock), the rest summed
  const auto w = c.warnings_now();
  INFO(w.size() << " warnings");
  CHECK(w.size() <= 2 * 11);
  CHECK(std::any_of(w.begin(), w.end(), [](const std::string& line) {
    return line.find("new time base") != std::string::npos &&
           line.find("more since the last such note") != std::string::npos;
  }));
}
