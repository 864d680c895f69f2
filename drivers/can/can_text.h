#pragma once
// What the two text forms of CAN frames (candump logs, the socketcand protocol) share: the
// timestamp's seconds and the data bytes' upper-case hexadecimal digits.
#include <cstdint>

namespace sonarloop::can {

inline constexpr std::int64_t kNsPerSecond = 1'000'000'000;
inline constexpr char kHexDigits[] = "0123456789ABCDEF";

}  // namespace sonarloop::can
