#include "drivers/n2k/can_id.h"

namespace sonarloop::n2k {

std::uint32_t encode_can_id(const N2kId& id) {
  const std::uint32_t prio = static_cast<std::uint32_t>(id.priority & 0x7u) << 26;
  const std::uint32_t pgn = id.pgn & kPgnMask;
  if (is_pdu2(pgn)) return prio | (pgn << 8) | id.source;
  // PDU1: R, DP and PF from the PGN, PS = destination address
  return prio | ((pgn & 0x3FF00u) << 8) | (static_cast<std::uint32_t>(id.destination) << 8) |
         id.source;
}

N2kId decode_can_id(std::uint32_t can_id) {
  N2kId out;
  out.priority = static_cast<std::uint8_t>((can_id >> 26) & 0x7u);
  out.source = static_cast<std::uint8_t>(can_id & 0xFFu);
  const std::uint32_t ps = (can_id >> 8) & 0xFFu;
  const std::uint32_t pgn_high = (can_id >> 8) & 0x3FF00u;  // R, DP, PF
  if (is_pdu2(pgn_high)) {
    out.pgn = pgn_high | ps;
    out.destination = kAddressGlobal;
  } else {
    out.pgn = pgn_high;
    out.destination = static_cast<std::uint8_t>(ps);
  }
  return out;
}

}  // namespace sonarloop::n2k
