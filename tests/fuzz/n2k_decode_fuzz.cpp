// The NMEA 2000 decoders (drivers/n2k/messages.h) on CAN frames built from the input: 4 bytes of
// identifier, 1 of length, up to 8 of payload, repeated.
#include <algorithm>

#include "drivers/n2k/messages.h"
#include "tests/fuzz/fuzz_support.h"

using namespace sonarloop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::size_t i = 0;
  while (i + 5 <= size) {
    can::CanFrame f;
    f.id = (static_cast<std::uint32_t>(data[i]) | static_cast<std::uint32_t>(data[i + 1]) << 8 |
            static_cast<std::uint32_t>(data[i + 2]) << 16 |
            static_cast<std::uint32_t>(data[i + 3]) << 24) &
           0x1FFFFFFFu;
    f.len = static_cast<std::uint8_t>(data[i + 4] % 9);
    i += 5;
    const std::size_t n = std::min<std::size_t>(f.len, size - i);
    std::copy(data + i, data + i + n, f.data.begin());
    i += n;
    (void)n2k::decode_any(f);
  }
  return 0;
}
