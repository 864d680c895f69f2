#pragma once
// Shared bits of the libFuzzer harnesses (tests/fuzz/*_fuzz.cpp, built with -DSONARLOOP_FUZZ=ON
// by scripts/fuzz.sh): each harness feeds one parser bytes from the fuzzer and accepts exactly two
// outcomes, a result or a refusal (std::exception); anything else (a crash, a sanitizer report, a
// hang, unbounded memory) is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>

namespace sonarloop::fuzz {

inline std::span<const std::uint8_t> bytes(const std::uint8_t* data, std::size_t size) {
  return {data, size};
}

// A file holding the input, for parsers that read paths; rewritten on every call. One per
// process (libFuzzer runs inputs one at a time), in $TMPDIR or /tmp.
inline const std::string& write_input_file(const std::uint8_t* data, std::size_t size,
                                           const char* suffix) {
  static const std::string path = [&] {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir && *dir ? dir : "/tmp") + "/sonarloop-fuzz-" +
           std::to_string(::getpid()) + suffix;
  }();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();  // the harness cannot run: not a finding in the parser
  if (size && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

}  // namespace sonarloop::fuzz
