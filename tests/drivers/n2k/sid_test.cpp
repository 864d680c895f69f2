#include "drivers/n2k/sid.h"

#include <catch2/catch.hpp>

using sonarloop::n2k::N2kSid;

TEST_CASE("n2k sid: counts 0..252 and wraps, never 253..255") {
  N2kSid sid;
  CHECK(sid.current() == 0);
  for (int i = 1; i <= 252; ++i)
    CHECK(sid.advance() == i);
  CHECK(sid.advance() == 0);
  CHECK(sid.current() == 0);
  for (int i = 0; i < 2000; ++i)
    CHECK(sid.advance() <= 252);
  CHECK(N2kSid(200).current() == 200);
  CHECK(N2kSid(255).current() == 0);  // an invalid start is reset
}
