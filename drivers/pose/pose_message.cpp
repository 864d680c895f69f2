#include "drivers/pose/pose_message.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace sonarloop::pose {
namespace {

// Byte offsets of the fields (pose_message.md).
constexpr std::size_t kOffMagic = 0;
constexpr std::size_t kOffVersion = 4;
constexpr std::size_t kOffSize = 6;
constexpr std::size_t kOffSequence = 8;
constexpr std::size_t kOffFlags = 12;
constexpr std::size_t kOffTime = 16;
constexpr std::size_t kOffLatitude = 24;
constexpr std::size_t kOffLongitude = 32;
constexpr std::size_t kOffDepth = 40;
constexpr std::size_t kOffAltitude = 48;
constexpr std::size_t kOffHeading = 56;
constexpr std::size_t kOffPitch = 64;
constexpr std::size_t kOffRoll = 72;
static_assert(kOffRoll + 8 == kPoseMessageBytes);

// Largest magnitude accepted for an angle: one full turn either way.
constexpr double kMaxAngleRad = 2.0 * std::numbers::pi;

// little-endian stores and loads of unsigned integers of `bytes` bytes
void put_le(std::uint8_t* p, std::uint64_t v, std::size_t bytes) {
  for (std::size_t i = 0; i < bytes; ++i)
    p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
std::uint64_t get_le(const std::uint8_t* p, std::size_t bytes) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < bytes; ++i)
    v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return v;
}
void put_f64(std::uint8_t* p, double v) {
  put_le(p, std::bit_cast<std::uint64_t>(v), 8);
}
double get_f64(const std::uint8_t* p) {
  return std::bit_cast<double>(get_le(p, 8));
}

// NaN (not available) or finite within [lo, hi].
bool available_in(double v, double lo, double hi) {
  return std::isnan(v) || (v >= lo && v <= hi);
}

}  // namespace

std::array<std::uint8_t, kPoseMessageBytes> encode_pose_message(const PoseMessage& m) {
  std::array<std::uint8_t, kPoseMessageBytes> out{};
  std::uint8_t* p = out.data();
  for (std::size_t i = 0; i < kPoseMessageMagic.size(); ++i)
    p[kOffMagic + i] = kPoseMessageMagic[i];
  put_le(p + kOffVersion, kPoseMessageVersion, 2);
  put_le(p + kOffSize, kPoseMessageBytes, 2);
  put_le(p + kOffSequence, m.sequence, 4);
  put_le(p + kOffFlags, m.flags, 4);
  put_le(p + kOffTime, static_cast<std::uint64_t>(m.time_unix_ns), 8);
  put_f64(p + kOffLatitude, m.latitude_deg);
  put_f64(p + kOffLongitude, m.longitude_deg);
  put_f64(p + kOffDepth, m.depth_m);
  put_f64(p + kOffAltitude, m.altitude_m);
  put_f64(p + kOffHeading, m.heading_rad);
  put_f64(p + kOffPitch, m.pitch_rad);
  put_f64(p + kOffRoll, m.roll_rad);
  return out;
}

std::optional<PoseMessage> decode_pose_message(std::span<const std::uint8_t> datagram,
                                               std::string& error) {
  if (datagram.size() != kPoseMessageBytes) {
    error = "pose message of " + std::to_string(datagram.size()) + " bytes, expected " +
            std::to_string(kPoseMessageBytes);
    return std::nullopt;
  }
  const std::uint8_t* p = datagram.data();
  for (std::size_t i = 0; i < kPoseMessageMagic.size(); ++i) {
    if (p[kOffMagic + i] != kPoseMessageMagic[i]) {
      char text[64];
      std::snprintf(text, sizeof text, "bad magic %02X %02X %02X %02X, expected 'SLPM'", p[0], p[1],
                    p[2], p[3]);
      error = text;
      return std::nullopt;
    }
  }
  const auto version = static_cast<std::uint16_t>(get_le(p + kOffVersion, 2));
  if (version != kPoseMessageVersion) {
    error = "pose message version " + std::to_string(version) + " is not supported (only " +
            std::to_string(kPoseMessageVersion) + ")";
    return std::nullopt;
  }
  const auto size = static_cast<std::uint16_t>(get_le(p + kOffSize, 2));
  if (size != kPoseMessageBytes) {
    error = "pose message size field " + std::to_string(size) + " is not " +
            std::to_string(kPoseMessageBytes);
    return std::nullopt;
  }
  PoseMessage m;
  m.sequence = static_cast<std::uint32_t>(get_le(p + kOffSequence, 4));
  m.flags = static_cast<std::uint32_t>(get_le(p + kOffFlags, 4));
  m.time_unix_ns = static_cast<std::int64_t>(get_le(p + kOffTime, 8));
  m.latitude_deg = get_f64(p + kOffLatitude);
  m.longitude_deg = get_f64(p + kOffLongitude);
  m.depth_m = get_f64(p + kOffDepth);
  m.altitude_m = get_f64(p + kOffAltitude);
  m.heading_rad = get_f64(p + kOffHeading);
  m.pitch_rad = get_f64(p + kOffPitch);
  m.roll_rad = get_f64(p + kOffRoll);

  if (!available_in(m.latitude_deg, -90.0, 90.0) || !available_in(m.longitude_deg, -180.0, 180.0)) {
    error = "latitude " + std::to_string(m.latitude_deg) + " / longitude " +
            std::to_string(m.longitude_deg) + " outside +-90 / +-180 degrees";
    return std::nullopt;
  }
  if (std::isnan(m.latitude_deg) != std::isnan(m.longitude_deg)) {
    error = "only one of latitude and longitude is available (both or neither)";
    return std::nullopt;
  }
  if (std::isinf(m.depth_m) || std::isinf(m.altitude_m)) {
    error = "depth or altitude is infinite (use NaN for not available)";
    return std::nullopt;
  }
  for (double a : {m.heading_rad, m.pitch_rad, m.roll_rad}) {
    if (!available_in(a, -kMaxAngleRad, kMaxAngleRad)) {
      error = "angle " + std::to_string(a) + " rad outside +-2 pi (angles are in radians)";
      return std::nullopt;
    }
  }
  return m;
}

}  // namespace sonarloop::pose
