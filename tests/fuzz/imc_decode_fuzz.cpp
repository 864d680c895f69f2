// The IMC packet decoder (drivers/imc/imc_codec.h) on one datagram. A packet it accepts is
// encoded again (little-endian) and decoded again: the second encoding equals the first (no
// field lost or changed by a round trip, whatever the byte order the input came in).
#include <cstdlib>
#include <vector>

#include "drivers/imc/imc_codec.h"
#include "tests/fuzz/fuzz_support.h"

using namespace sonarloop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  imc::Packet p;
  if (imc::decode(fuzz::bytes(data, size), p) != imc::DecodeStatus::kOk) return 0;
  std::vector<std::uint8_t> once, twice;
  imc::encode_message(p.header, p.message, once);
  imc::Packet q;
  if (imc::decode(once, q) != imc::DecodeStatus::kOk) std::abort();
  imc::encode_message(q.header, q.message, twice);
  if (once != twice) std::abort();
  return 0;
}
