// The UDP pose message decoder (drivers/pose/pose_message.h) on one datagram.
#include <string>

#include "drivers/pose/pose_message.h"
#include "tests/fuzz/fuzz_support.h"

using namespace sonarloop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string error;
  (void)pose::decode_pose_message(fuzz::bytes(data, size), error);
  return 0;
}
