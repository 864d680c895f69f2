#pragma once
// The default warning sink of the emulator's sources (replay, HIL pose input) when the caller
// gives none: one "warning: ..." line on stderr.
#include <cstdio>
#include <string>

namespace sonarloop::emulator {

inline void warn_on_stderr(const std::string& text) {
  std::fprintf(stderr, "warning: %s\n", text.c_str());
}

}  // namespace sonarloop::emulator
