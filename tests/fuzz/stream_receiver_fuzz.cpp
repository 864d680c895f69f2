// The onboard UDP stream receiver (atr/stream_receiver.h) on datagrams cut from the input: a
// 2-byte little-endian length, then that many bytes, repeated.
#include <algorithm>

#include "atr/stream_receiver.h"
#include "tests/fuzz/fuzz_support.h"

using namespace sonarloop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::size_t pings = 0;
  atr::StreamReceiver r(atr::ReceiverOptions{},
                        [&](const xtf::XtfFileHeader&, const xtf::XtfPing&) { ++pings; });
  std::size_t i = 0;
  while (i + 2 <= size) {
    const std::size_t n = std::min<std::size_t>(
        static_cast<std::size_t>(data[i]) | static_cast<std::size_t>(data[i + 1]) << 8,
        size - i - 2);
    (void)r.feed(fuzz::bytes(data + i + 2, n));
    i += 2 + n;
  }
  r.flush();
  return 0;
}
