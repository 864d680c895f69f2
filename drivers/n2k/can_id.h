#pragma once
// NMEA 2000 29-bit CAN identifiers (ISO 11783 / SAE J1939 layout; docs/formats.md §2.1).
//
//   bits 28-26 priority (0 highest .. 7) | 25 reserved (EDP) | 24 data page | 23-16 PDU format PF
//   | 15-8 PDU specific PS | 7-0 source address SA
//
// PF < 240 (PDU1) is addressed: PS is the destination address and not part of the PGN.
// PF >= 240 (PDU2) is broadcast: PS is the group extension, i.e. the PGN's low byte.
// Example: PGN 129025, priority 2, source 0x23 -> 0x09F80123.
#include <cstdint>

namespace sonarloop::n2k {

inline constexpr std::uint8_t kAddressGlobal = 0xFF;    // broadcast destination
inline constexpr std::uint32_t kPgnMask = 0x3FFFF;      // 18 bits: R, DP, PF, PS
inline constexpr std::uint8_t kPdu2MinPduFormat = 240;  // PF >= 240: broadcast (PDU2)

struct N2kId {
  std::uint8_t priority = 6;                  // 0 (highest) .. 7
  std::uint32_t pgn = 0;                      // parameter group number, 18 bits
  std::uint8_t source = 0;                    // source address 0..253 (254 null, 255 global)
  std::uint8_t destination = kAddressGlobal;  // PDU1 only; PDU2 frames are always global

  friend bool operator==(const N2kId&, const N2kId&) = default;
};

// True if the PGN is broadcast-only (PDU2: PF >= 240).
constexpr bool is_pdu2(std::uint32_t pgn) {
  return ((pgn >> 8) & 0xFFu) >= kPdu2MinPduFormat;
}

// 29-bit identifier (no CAN_EFF_FLAG). Priority is masked to 3 bits and the PGN to 18 bits; for a
// PDU1 PGN the low byte is replaced by the destination, for PDU2 the destination is ignored.
std::uint32_t encode_can_id(const N2kId& id);

// Inverse of encode_can_id. Bits above bit 28 are ignored. PDU2 ids decode with destination 255.
N2kId decode_can_id(std::uint32_t can_id);

}  // namespace sonarloop::n2k
