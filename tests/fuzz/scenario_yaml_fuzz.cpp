// The scenario loader (config/loader/scenario_loader.h: YAML, scene, sonar, vehicle) on the
// input as YAML text.
#include <exception>
#include <string>

#include "config/loader/scenario_loader.h"
#include "tests/fuzz/fuzz_support.h"

using namespace sonarloop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)config::parse_scenario(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
  } catch (const std::exception&) {
  }
  return 0;
}
