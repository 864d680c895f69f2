#pragma once
// What the pose input's tests share (pose_source_test.cpp: the sources; pose_message_test.cpp:
// the message; pose_plausibility_test.cpp: implausible poses): an origin, an injected clock, a
// bounded wait, and a sample message.
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <thread>

#include "common/geodesy.h"
#include "drivers/net/udp_sender.h"
#include "emulator/pose_message.h"

namespace sonarloop::emulator::pose_test {

inline const GeoPoint kOrigin{59.9, 10.75};
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The injected clock: tests set the value that the source reads at each receipt.
struct InjectedClock {
  std::atomic<std::int64_t> value{0};
  std::atomic<int> calls{0};
  std::function<std::int64_t()> fn() {
    return [this] {
      ++calls;
      return value.load();
    };
  }
};

// Polls `done` every 5 ms for up to 20 s (a bound against hangs, not a timing assertion).
inline bool wait_until(const std::function<bool()>& done) {
  for (int i = 0; i < 4000; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

// Lets a silent source's thread run through several receive timeouts.
inline void let_time_pass() {
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
}

inline PoseMessage message(std::uint32_t seq) {
  PoseMessage m;
  m.sequence = seq;
  m.time_unix_ns = 1'767'225'600'000'000'000 + static_cast<std::int64_t>(seq) * 100'000'000;
  m.latitude_deg = 59.9012345 + 1e-6 * seq;
  m.longitude_deg = 10.7523456;
  m.depth_m = 35.5;
  m.altitude_m = 12.25;
  m.heading_rad = 1.5;
  m.pitch_rad = -0.02;
  m.roll_rad = 0.01;
  return m;
}

inline void send(net::UdpSender& tx, const PoseMessage& m) {
  const auto bytes = encode_pose_message(m);
  REQUIRE(tx.send(bytes));
}

}  // namespace sonarloop::emulator::pose_test
