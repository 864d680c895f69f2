#pragma once
// NMEA 2000 sequence id (SID, docs/formats.md §2.2): ties together PGNs sampled at the same
// instant. Values run 0..252 and wrap; 255 means "not available". Increment once per sample cycle,
// give every PGN of that cycle the same value. Not thread-safe: one counter per publishing thread.
#include <cstdint>

namespace sonarloop::n2k {

class N2kSid {
 public:
  static constexpr std::uint8_t kMax = 252;

  explicit N2kSid(std::uint8_t first = 0) : value_(first > kMax ? 0 : first) {}
  // The SID of the current cycle.
  std::uint8_t current() const { return value_; }
  // Starts a new cycle and returns its SID (252 wraps to 0).
  std::uint8_t advance() {
    value_ = value_ >= kMax ? 0 : static_cast<std::uint8_t>(value_ + 1);
    return value_;
  }

 private:
  std::uint8_t value_;
};

}  // namespace sonarloop::n2k
