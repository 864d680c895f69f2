#include "drivers/n2k/field.h"

#include <catch2/catch.hpp>
#include <limits>

using namespace sonarloop::n2k;

TEST_CASE("n2k field: sentinel values follow canboat's top-of-range rule") {
  CHECK(raw_not_available(8, false) == 0xFFu);
  CHECK(raw_not_available(16, false) == 0xFFFFu);
  CHECK(raw_not_available(32, false) == 0xFFFFFFFFu);
  CHECK(raw_not_available(16, true) == 0x7FFFu);
  CHECK(raw_not_available(32, true) == 0x7FFFFFFFu);
  CHECK(raw_max_data(16, false) == 0xFFFC);
  CHECK(raw_max_data(16, true) == 0x7FFC);
  CHECK(raw_min_data(16, true) == -0x7FFF);
}

TEST_CASE("n2k field: bits are little-endian, LSB first, and can straddle bytes") {
  FrameBytes b{};
  put_bits(b, 0, 32, 0x23B5E600u);
  CHECK(b[0] == 0x00);
  CHECK(b[1] == 0xE6);
  CHECK(b[2] == 0xB5);
  CHECK(b[3] == 0x23);
  put_bits(b, 36, 8, 0xABu);  // straddles bytes 4 and 5
  CHECK(b[4] == 0xB0);
  CHECK(b[5] == 0x0A);
  CHECK(get_bits(b, 36, 8) == 0xABu);
  put_bits(b, 48, 16, static_cast<std::uint64_t>(-349));
  CHECK(get_bits_signed(b, 48, 16) == -349);
  CHECK(b[6] == 0xA3);
  CHECK(b[7] == 0xFE);
}

TEST_CASE("n2k field: rounding, saturation and wrapping never produce a sentinel") {
  const ScaledField u16{16, false, 0.01, 0.0, 655.32, OutOfRange::kClamp};
  CHECK(scale_to_raw(2.40, u16) == 240);
  CHECK(scale_to_raw(2.404999, u16) == 240);
  CHECK(scale_to_raw(2.405001, u16) == 241);
  CHECK(scale_to_raw(1e9, u16) == 0xFFFC);
  CHECK(scale_to_raw(std::numeric_limits<double>::infinity(), u16) == 0xFFFC);
  CHECK(scale_to_raw(-5.0, u16) == 0);
  CHECK(scale_to_raw(std::nullopt, u16) == 0xFFFF);
  CHECK(scale_to_raw(std::numeric_limits<double>::quiet_NaN(), u16) == 0xFFFF);

  const ScaledField s16{16, true, 0.001, -32.767, 32.764, OutOfRange::kClamp};
  CHECK(scale_to_raw(-0.5, s16) == -500);
  CHECK(scale_to_raw(100.0, s16) == 0x7FFC);
  CHECK(scale_to_raw(-100.0, s16) == -0x7FFF);

  const ScaledField ang{16, true, 1e-4, -3.141592653589793, 3.141592653589793, OutOfRange::kWrap};
  CHECK(scale_to_raw(3.141592653589793 + 0.1, ang) == scale_to_raw(-3.141592653589793 + 0.1, ang));
  CHECK(scale_to_raw(-0.1 - 4 * 3.141592653589793, ang) == -1000);

  // decoding: the three top values are "no value"
  CHECK_FALSE(raw_to_value(0xFFFF, u16).has_value());
  CHECK_FALSE(raw_to_value(0xFFFE, u16).has_value());
  CHECK_FALSE(raw_to_value(0xFFFD, u16).has_value());
  REQUIRE(raw_to_value(0xFFFC, u16).has_value());
  CHECK(*raw_to_value(0xFFFC, u16) == Approx(655.32));
  CHECK_FALSE(raw_to_value(0x7FFF, s16).has_value());
  CHECK(*raw_to_value(-0x8000, s16) == Approx(-32.768));
}
