// The socketcand protocol (drivers/can/socketcand_protocol.h): element splitting and the frame
// and send parsers of the server and client sides, on each "< ... >" element of the input.
#include <string>
#include <string_view>

#include "drivers/can/socketcand_protocol.h"
#include "tests/fuzz/fuzz_support.h"

using namespace sonarloop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::string error;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t open = text.find('<', pos);
    if (open == std::string_view::npos) break;
    const std::size_t close = text.find('>', open);
    const std::string_view element = text.substr(
        open, close == std::string_view::npos ? std::string_view::npos : close - open + 1);
    (void)can::split_socketcand_element(element);
    (void)can::parse_socketcand_frame(element, error);
    (void)can::parse_socketcand_send(element, error);
    if (close == std::string_view::npos) break;
    pos = close + 1;
  }
  return 0;
}
