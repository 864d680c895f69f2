#pragma once
// The UDP pose message: how an external vehicle (a vehicle computer in a hardware-in-the-loop
// rig, a simulator, a script) tells the emulator where it is, for `sonarloop run --pose-from
// udp:HOST:PORT` (docs/style.md habit 7: a versioned packet with magic, sequence and absolute
// timestamp). Byte layout, semantics and an example datagram: drivers/pose/pose_message.md.
//
//   off size type     field
//     0    4 char[4]  magic "SLPM"
//     4    2 u16      version = 1
//     6    2 u16      size = 80 (bytes of the whole message)
//     8    4 u32      sequence (the sender's message counter, +1 per message, wraps)
//    12    4 u32      flags (reserved: senders write 0, receivers ignore)
//    16    8 i64      time_unix_ns (UTC of the pose sample, ns since 1970-01-01; 0 = unknown)
//    24    8 f64      latitude_deg (WGS84)
//    32    8 f64      longitude_deg (WGS84)
//    40    8 f64      depth_m (below the sea surface, + down)
//    48    8 f64      altitude_m (above the seabed)
//    56    8 f64      heading_rad (clockwise from true north)
//    64    8 f64      pitch_rad (+ nose up)
//    72    8 f64      roll_rad (+ starboard down)
// Little-endian, no padding. A NaN field is "not available"; latitude and longitude are available
// together or not at all. Angles and frames are those of sim/frames.h (heading = yaw ψ).
//
// Decoding is strict: wrong length, magic, version or size field, infinite values, latitude
// outside ±90°, longitude outside ±180°, an angle beyond ±2π, or only one of latitude/longitude
// are errors (a message, never an exception).
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>

namespace sonarloop::pose {

inline constexpr std::array<std::uint8_t, 4> kPoseMessageMagic = {'S', 'L', 'P', 'M'};
inline constexpr std::uint16_t kPoseMessageVersion = 1;
inline constexpr std::size_t kPoseMessageBytes = 80;

struct PoseMessage {
  static constexpr double kNotAvailable = std::numeric_limits<double>::quiet_NaN();
  std::uint32_t sequence = 0;
  std::uint32_t flags = 0;        // reserved, 0
  std::int64_t time_unix_ns = 0;  // 0 = unknown
  double latitude_deg = kNotAvailable;
  double longitude_deg = kNotAvailable;
  double depth_m = kNotAvailable;
  double altitude_m = kNotAvailable;
  double heading_rad = kNotAvailable;
  double pitch_rad = kNotAvailable;
  double roll_rad = kNotAvailable;
};

// The 80-byte datagram of a message (fields are written as given; no checks).
std::array<std::uint8_t, kPoseMessageBytes> encode_pose_message(const PoseMessage& m);

// Decodes one datagram. nullopt with `error` set to what is wrong (e.g. "bad magic 53 4C 50 58,
// expected 'SLPM'") if it is not a valid version-1 pose message.
std::optional<PoseMessage> decode_pose_message(std::span<const std::uint8_t> datagram,
                                               std::string& error);

}  // namespace sonarloop::pose
