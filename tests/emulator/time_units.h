#pragma once
// Time units for the emulator's tests, whose clocks count nanoseconds.
#include <cstdint>

namespace sonarloop::testing {

inline constexpr std::int64_t kMs = 1'000'000;  // one millisecond, in nanoseconds

}  // namespace sonarloop::testing
