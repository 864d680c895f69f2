#pragma once
// Integer division rounding towards minus infinity (C++'s `/` rounds towards zero), for tile and
// cell indices of coordinates that may be negative.
#include <cstdint>

namespace sonarloop {

// ⌊a / b⌋ for b != 0.
inline std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

}  // namespace sonarloop
