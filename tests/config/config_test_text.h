#pragma once
// Text helpers shared by the loader tests that write YAML values themselves.
#include <cstdio>
#include <string>

namespace sonarloop::testing {

// `v` with enough digits (%.17g) to read back as exactly the same double.
inline std::string real_text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace sonarloop::testing
