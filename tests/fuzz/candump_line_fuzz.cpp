// The candump log line parser (drivers/can/candump_log.h), line by line.
#include <string>
#include <string_view>

#include "drivers/can/candump_log.h"
#include "tests/fuzz/fuzz_support.h"

using namespace sonarloop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  can::CandumpRecord record;
  std::string error;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    (void)can::parse_candump_line(text.substr(start, end - start), record, error);
    start = end + 1;
  }
  return 0;
}
