// CRC-32 (drivers/io/crc32.h): the catalogue's check value, the empty input, and the incremental
// form equal to the whole.
#include "drivers/io/crc32.h"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

using namespace sonarloop;

TEST_CASE("crc32: the check value, and incremental equals whole") {
  const std::string check = "123456789";
  const std::span<const std::uint8_t> b(reinterpret_cast<const std::uint8_t*>(check.data()),
                                        check.size());
  CHECK(io::crc32(b) == 0xCBF43926u);
  CHECK(io::crc32({}) == 0u);
  CHECK(io::crc32_update(io::crc32_update(0, b.first(4)), b.subspan(4)) == 0xCBF43926u);
  std::uint32_t c = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
    c = io::crc32_update(c, b.subspan(i, 1));
  CHECK(c == 0xCBF43926u);
}
