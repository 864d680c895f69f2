// The XTF file readers (drivers/xtf/xtf_file.h), on a file holding the input.
#include <exception>

#include "drivers/xtf/xtf_file.h"
#include "tests/fuzz/fuzz_support.h"

using namespace sonarloop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = fuzz::write_input_file(data, size, ".xtf");
  try {
    (void)xtf::read_all_pings(path);
  } catch (const std::exception&) {
  }
  try {
    (void)xtf::read_raw_packets(path);
  } catch (const std::exception&) {
  }
  return 0;
}
