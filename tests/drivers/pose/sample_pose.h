#pragma once
// A sample pose message (drivers/pose/pose_message.h), for the tests of the message and of the
// pose input that reads it (tests/emulator/pose_source_support.h).
#include <cstdint>

#include "drivers/pose/pose_message.h"

namespace sonarloop::testing {

inline pose::PoseMessage sample_pose_message(std::uint32_t seq) {
  pose::PoseMessage m;
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

}  // namespace sonarloop::testing
