#pragma once
// The APL-UW parameters of a sediment named by its key, for the APL tests.
#include <catch2/catch.hpp>

#include "sim/acoustics/apl_sediment.h"
#include "sim/seabed/sediment.h"

namespace sonarloop::testing {

// The sediment `key` (which must exist) as APL-UW parameters.
inline acoustics::AplSediment apl_sediment_by_key(const char* key) {
  const auto id = seabed::find_sediment(key);
  REQUIRE(id.has_value());
  return acoustics::apl_sediment(*id);
}

}  // namespace sonarloop::testing
