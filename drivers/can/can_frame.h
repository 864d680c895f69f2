#pragma once
// A classic CAN 2.0 data frame as it travels between the NMEA 2000 codec and the CAN transports.
// Plain data: the id carries no SocketCAN flag bits (CAN_EFF_FLAG etc.); `extended` says whether
// it is a 29-bit (EFF) or an 11-bit (SFF) identifier. NMEA 2000 uses extended frames only.
#include <array>
#include <cstdint>

namespace sonarloop::can {

inline constexpr std::uint32_t kCanSffMask = 0x7FFu;       // 11-bit identifier
inline constexpr std::uint32_t kCanEffMask = 0x1FFFFFFFu;  // 29-bit identifier
inline constexpr std::uint8_t kCanMaxDataBytes = 8;        // classic CAN payload

struct CanFrame {
  std::uint32_t id = 0;                // 29-bit (extended) or 11-bit identifier, no flag bits
  bool extended = true;                // EFF (29-bit) frame
  std::uint8_t len = 0;                // payload length in bytes, 0..8
  std::array<std::uint8_t, 8> data{};  // payload; bytes at and beyond len are zero

  friend bool operator==(const CanFrame&, const CanFrame&) = default;
};

}  // namespace sonarloop::can
