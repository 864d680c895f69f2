#pragma once
// What the pose input's tests share (pose_source_test.cpp: the sources;
// pose_plausibility_test.cpp: implausible poses): an origin, an injected clock, a bounded wait,
// and a sample message (tests/drivers/pose/sample_pose.h).
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <thread>

#include "common/geodesy.h"
#include "drivers/net/udp_sender.h"
#include "drivers/pose/pose_message.h"
#include "tests/drivers/pose/sample_pose.h"

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

inline pose::PoseMessage message(std::uint32_t seq) {
  return testing::sample_pose_message(seq);
}

inline void send(net::UdpSender& tx, const pose::PoseMessage& m) {
  const auto bytes = pose::encode_pose_message(m);
  REQUIRE(tx.send(bytes));
}

}  // namespace sonarloop::emulator::pose_test
