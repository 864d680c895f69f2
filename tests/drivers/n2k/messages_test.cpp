#include "drivers/n2k/messages.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "tests/support/test_rng.h"

using namespace sonarloop::n2k;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr std::uint8_t kSource = 0x23;

// "09F80123#00E6B523B1AC6A06" -> frame
CanFrame frame_from_text(const std::string& text) {
  CanFrame f;
  const auto hash = text.find('#');
  f.id = static_cast<std::uint32_t>(std::stoul(text.substr(0, hash), nullptr, 16));
  f.extended = true;
  const std::string data = text.substr(hash + 1);
  f.len = static_cast<std::uint8_t>(data.size() / 2);
  for (std::size_t i = 0; i < f.len; ++i)
    f.data[i] = static_cast<std::uint8_t>(std::stoul(data.substr(2 * i, 2), nullptr, 16));
  return f;
}

std::string frame_to_text(const CanFrame& f) {
  char buf[64];
  int n = std::snprintf(buf, sizeof buf, "%08X#", static_cast<unsigned>(f.id));
  for (int i = 0; i < f.len; ++i)
    n += std::snprintf(buf + n, sizeof buf - static_cast<std::size_t>(n), "%02X", f.data[i]);
  return buf;
}

// Decoded value within half a resolution step of the original (angles compared modulo period).
void check_field(std::optional<double> original, std::optional<double> decoded, double resolution,
                 double period = 0.0) {
  REQUIRE(original.has_value() == decoded.has_value());
  if (!original) return;
  double diff = *decoded - *original;
  if (period > 0.0) diff -= period * std::round(diff / period);
  CHECK(std::abs(diff) <= 0.5 * resolution * (1.0 + 1e-6));
}

// Random value in [lo, hi), or nullopt one time in eight.
std::optional<double> maybe(sonarloop::testing::TestRng& rng, double lo, double hi) {
  if (rng.below(8) == 0) return std::nullopt;
  return rng.uniform(lo, hi);
}

std::uint8_t random_sid(sonarloop::testing::TestRng& rng) {
  const auto s = static_cast<std::uint8_t>(rng.below(254));
  return s == 253 ? kSidNotAvailable : s;
}

template <class T>
T round_trip(const T& m) {
  const CanFrame f = encode(m, kSource);
  CHECK(f.extended);
  CHECK(f.len == 8);
  const N2kId id = decode_can_id(f.id);
  CHECK(id.pgn == T::kPgn);
  CHECK(id.source == kSource);
  CHECK(id.priority == T::kDefaultPriority);
  const Decoded<T> d = decode<T>(f);
  REQUIRE(d.has_value());
  // decode_any agrees with decode<T>
  const Decoded<N2kMessage> any = decode_any(f);
  REQUIRE(any.has_value());
  REQUIRE(std::holds_alternative<T>(*any));
  CHECK(std::get<T>(*any) == *d);
  // re-encoding the decoded message reproduces the frame exactly
  CHECK(encode(*d, kSource) == f);
  return *d;
}

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kSamples = 5000;

}  // namespace

TEST_CASE("n2k: the eight reference frames of docs/formats.md 2.4 encode byte-exactly") {
  PositionRapidUpdate pos{59.9123456, 10.7654321};
  CHECK(frame_to_text(encode(pos, kSource)) == "09F80123#00E6B523B1AC6A06");

  CogSogRapidUpdate cog{7, DirectionReference::kTrue, 45.0 * kDeg, 2.50};
  CHECK(frame_to_text(encode(cog, kSource)) == "09F80223#07FCAE1EFA00FFFF");

  VesselHeading hdg{7, 123.4 * kDeg, std::nullopt, -2.0 * kDeg, DirectionReference::kTrue};
  CHECK(frame_to_text(encode(hdg, kSource)) == "09F11223#072154FF7FA3FEFC");

  Attitude att{7, 3.0 * kDeg, -1.5 * kDeg, 2.25 * kDeg};
  CHECK(frame_to_text(encode(att, kSource)) == "0DF11923#070C02FAFE8901FF");

  WaterDepth depth{7, 42.37, -0.500, std::nullopt};
  CHECK(frame_to_text(encode(depth, kSource)) == "0DF50B23#078D1000000CFEFF");

  RateOfTurn rot{7, 1.0 * kDeg};
  CHECK(frame_to_text(encode(rot, kSource)) == "09F11323#07A9850800FFFFFF");

  SystemTime time{7, SystemTimeSource::kGps, 19675.0, 22 * 3600 + 13 * 60 + 19.1234};
  CHECK(frame_to_text(encode(time, kSource)) == "0DF01023#07F0DB4CC2E5AE2F");
  // the same from a UNIX time: 2023-11-14 22:13:19.1234 UTC
  CHECK(encode(system_time_from_unix_ns(1'699'999'999'123'400'000, 7), kSource) ==
        encode(time, kSource));

  SpeedWaterReferenced stw{7, 2.40, std::nullopt, WaterReference::kDoppler, 0};
  CHECK(frame_to_text(encode(stw, kSource)) == "09F50323#07F000FFFF02F0FF");
}

TEST_CASE("n2k: the reference frames decode to the values canboat prints") {
  const auto pos = decode<PositionRapidUpdate>(frame_from_text("09F80123#00E6B523B1AC6A06"));
  REQUIRE(pos);
  CHECK(*pos->latitude_deg == Approx(59.9123456).margin(1e-9));
  CHECK(*pos->longitude_deg == Approx(10.7654321).margin(1e-9));

  const auto hdg = decode<VesselHeading>(frame_from_text("09F11223#072154FF7FA3FEFC"));
  REQUIRE(hdg);
  CHECK(hdg->sid == 7);
  CHECK(*hdg->heading_rad / kDeg == Approx(123.4).margin(0.01));
  CHECK_FALSE(hdg->deviation_rad.has_value());
  CHECK(*hdg->variation_rad / kDeg == Approx(-2.0).margin(0.01));
  CHECK(hdg->reference == DirectionReference::kTrue);

  const auto depth = decode<WaterDepth>(frame_from_text("0DF50B23#078D1000000CFEFF"));
  REQUIRE(depth);
  CHECK(*depth->depth_m == Approx(42.37));
  CHECK(*depth->offset_m == Approx(-0.5));
  CHECK_FALSE(depth->range_m.has_value());

  const auto time = decode<SystemTime>(frame_from_text("0DF01023#07F0DB4CC2E5AE2F"));
  REQUIRE(time);
  CHECK(*time->date_days == 19675.0);
  CHECK(time->source == SystemTimeSource::kGps);
  CHECK(unix_ns_from_system_time(*time) == 1'699'999'999'123'400'000);

  const auto stw = decode<SpeedWaterReferenced>(frame_from_text("09F50323#07F000FFFF02F0FF"));
  REQUIRE(stw);
  CHECK(*stw->speed_water_mps == Approx(2.40));
  CHECK_FALSE(stw->speed_ground_mps.has_value());
  CHECK(stw->speed_water_type == WaterReference::kDoppler);
  CHECK(stw->speed_direction == 0);
}

TEST_CASE("n2k: reserved bits are ones and n/a fields are sentinels") {
  // everything not available
  CHECK(frame_to_text(encode(PositionRapidUpdate{}, kSource)) == "09F80123#FFFFFF7FFFFFFF7F");
  CHECK(frame_to_text(encode(CogSogRapidUpdate{}, kSource)) == "09F80223#FFFCFFFFFFFFFFFF");
  CHECK(frame_to_text(encode(VesselHeading{}, kSource)) == "09F11223#FFFFFFFF7FFF7FFC");
  CHECK(frame_to_text(encode(RateOfTurn{}, kSource)) == "09F11323#FFFFFFFF7FFFFFFF");
  CHECK(frame_to_text(encode(Attitude{}, kSource)) == "0DF11923#FFFF7FFF7FFF7FFF");
  CHECK(frame_to_text(encode(SpeedWaterReferenced{}, kSource)) == "09F50323#FFFFFFFFFFFFF0FF");
  CHECK(frame_to_text(encode(WaterDepth{}, kSource)) == "0DF50B23#FFFFFFFFFFFF7FFF");
  CHECK(frame_to_text(encode(SystemTime{}, kSource)) == "0DF01023#FFF0FFFFFFFFFFFF");

  // and the sentinels decode back to nullopt
  const auto a = decode<Attitude>(encode(Attitude{}, kSource));
  REQUIRE(a);
  CHECK(a->sid == kSidNotAvailable);
  CHECK_FALSE(a->yaw_rad);
  CHECK_FALSE(a->pitch_rad);
  CHECK_FALSE(a->roll_rad);
  // magnetic reference keeps the 6 reserved bits set
  VesselHeading mag;
  mag.reference = DirectionReference::kMagnetic;
  CHECK(encode(mag, kSource).data[7] == 0xFD);
}

TEST_CASE("n2k: out-of-range values saturate (or wrap) and never become sentinels") {
  WaterDepth d{1, 1e12, 1e6, 1e6};
  auto dd = decode<WaterDepth>(encode(d, kSource));
  REQUIRE(dd);
  REQUIRE(dd->depth_m);
  REQUIRE(dd->offset_m);
  REQUIRE(dd->range_m);
  CHECK(*dd->depth_m == Approx(42949672.92));
  CHECK(*dd->offset_m == Approx(32.764));
  CHECK(*dd->range_m == 2520.0);
  d = WaterDepth{1, -3.0, -1e6, -1.0};
  dd = decode<WaterDepth>(encode(d, kSource));
  CHECK(*dd->depth_m == 0.0);
  CHECK(*dd->offset_m == Approx(-32.767));
  CHECK(*dd->range_m == 0.0);

  const auto p = decode<PositionRapidUpdate>(encode(PositionRapidUpdate{95.0, 190.0}, kSource));
  CHECK(*p->latitude_deg == Approx(90.0));
  CHECK(*p->longitude_deg == Approx(-170.0));

  const auto r = decode<RateOfTurn>(encode(RateOfTurn{0, 1e6}, kSource));
  REQUIRE(r->rate_rad_per_s);
  CHECK(*r->rate_rad_per_s == Approx(2147483644 * 3.125e-8));

  const auto h = decode<VesselHeading>(
      encode(VesselHeading{0, -10.0 * kDeg, 190.0 * kDeg, -190.0 * kDeg}, kSource));
  CHECK(*h->heading_rad / kDeg == Approx(350.0).margin(0.01));
  CHECK(*h->deviation_rad / kDeg == Approx(-170.0).margin(0.01));
  CHECK(*h->variation_rad / kDeg == Approx(170.0).margin(0.01));

  const auto s = decode<CogSogRapidUpdate>(
      encode(CogSogRapidUpdate{0, DirectionReference::kTrue, 0.0, 1e9}, kSource));
  CHECK(*s->sog_mps == Approx(655.32));

  const auto t =
      decode<SystemTime>(encode(SystemTime{0, SystemTimeSource::kGps, 1e9, 1e9}, kSource));
  CHECK(*t->date_days == 65532.0);
  CHECK(*t->time_of_day_s == Approx(86400.9999));
}

TEST_CASE("n2k: decode rejects malformed frames with a reason") {
  CanFrame f = encode(Attitude{1, 0.1, 0.2, 0.3}, kSource);
  CHECK(decode<Attitude>(f).has_value());

  CanFrame short_frame = f;
  short_frame.len = 7;
  CHECK(decode<Attitude>(short_frame).error() == DecodeError::kWrongLength);
  CHECK(decode_any(short_frame).error() == DecodeError::kWrongLength);

  CanFrame sff = f;
  sff.extended = false;
  CHECK(decode<Attitude>(sff).error() == DecodeError::kNotExtended);
  CHECK(decode_any(sff).error() == DecodeError::kNotExtended);

  CHECK(decode<VesselHeading>(f).error() == DecodeError::kWrongPgn);

  CanFrame unknown = f;
  unknown.id = encode_can_id(N2kId{3, 130306, kSource, kAddressGlobal});  // wind data
  CHECK(decode_any(unknown).error() == DecodeError::kUnsupportedPgn);
  CHECK(std::string(to_string(DecodeError::kWrongLength)).find("8 bytes") != std::string::npos);

  // any source address and priority is accepted
  const CanFrame other = encode(Attitude{1, 0.1, 0.2, 0.3}, 0x80, 7);
  CHECK(decode_can_id(other.id).priority == 7);
  CHECK(decode<Attitude>(other).has_value());
}

TEST_CASE("n2k: seeded random round trip of every PGN within half a resolution step") {
  sonarloop::testing::TestRng rng(0x2001);
  const double pi = std::numbers::pi;
  for (int i = 0; i < kSamples; ++i) {
    {
      PositionRapidUpdate m{maybe(rng, -90.0, 90.0), maybe(rng, -180.0, 180.0)};
      const auto d = round_trip(m);
      check_field(m.latitude_deg, d.latitude_deg, 1e-7);
      check_field(m.longitude_deg, d.longitude_deg, 1e-7, 360.0);
    }
    {
      CogSogRapidUpdate m{random_sid(rng), static_cast<DirectionReference>(rng.below(4)),
                          maybe(rng, 0.0, kTwoPi), maybe(rng, 0.0, 655.32)};
      const auto d = round_trip(m);
      CHECK(d.sid == m.sid);
      CHECK(d.cog_reference == m.cog_reference);
      check_field(m.cog_rad, d.cog_rad, 1e-4, kTwoPi);
      check_field(m.sog_mps, d.sog_mps, 0.01);
    }
    {
      VesselHeading m{random_sid(rng), maybe(rng, 0.0, kTwoPi), maybe(rng, -pi, pi),
                      maybe(rng, -pi, pi), static_cast<DirectionReference>(rng.below(4))};
      const auto d = round_trip(m);
      CHECK(d.sid == m.sid);
      CHECK(d.reference == m.reference);
      check_field(m.heading_rad, d.heading_rad, 1e-4, kTwoPi);
      check_field(m.deviation_rad, d.deviation_rad, 1e-4, kTwoPi);
      check_field(m.variation_rad, d.variation_rad, 1e-4, kTwoPi);
    }
    {
      RateOfTurn m{random_sid(rng), maybe(rng, -67.1, 67.1)};
      const auto d = round_trip(m);
      CHECK(d.sid == m.sid);
      check_field(m.rate_rad_per_s, d.rate_rad_per_s, 3.125e-8);
    }
    {
      Attitude m{random_sid(rng), maybe(rng, -pi, pi), maybe(rng, -pi, pi), maybe(rng, -pi, pi)};
      const auto d = round_trip(m);
      CHECK(d.sid == m.sid);
      check_field(m.yaw_rad, d.yaw_rad, 1e-4, kTwoPi);
      check_field(m.pitch_rad, d.pitch_rad, 1e-4, kTwoPi);
      check_field(m.roll_rad, d.roll_rad, 1e-4, kTwoPi);
    }
    {
      const auto type = rng.below(6) == 5 ? WaterReference::kNotAvailable
                                          : static_cast<WaterReference>(rng.below(5));
      SpeedWaterReferenced m{random_sid(rng), maybe(rng, 0.0, 655.32), maybe(rng, 0.0, 655.32),
                             type, static_cast<std::uint8_t>(rng.below(16))};
      const auto d = round_trip(m);
      CHECK(d.sid == m.sid);
      CHECK(d.speed_water_type == m.speed_water_type);
      CHECK(d.speed_direction == m.speed_direction);
      check_field(m.speed_water_mps, d.speed_water_mps, 0.01);
      check_field(m.speed_ground_mps, d.speed_ground_mps, 0.01);
    }
    {
      WaterDepth m{random_sid(rng), maybe(rng, 0.0, 42949672.92), maybe(rng, -32.767, 32.764),
                   maybe(rng, 0.0, 2520.0)};
      const auto d = round_trip(m);
      CHECK(d.sid == m.sid);
      check_field(m.depth_m, d.depth_m, 0.01);
      check_field(m.offset_m, d.offset_m, 0.001);
      check_field(m.range_m, d.range_m, 10.0);
    }
    {
      std::optional<double> date;
      if (rng.below(8) != 0) date = static_cast<double>(rng.below(65533));
      SystemTime m{random_sid(rng), static_cast<SystemTimeSource>(rng.below(16)), date,
                   maybe(rng, 0.0, 86400.0)};
      const auto d = round_trip(m);
      CHECK(d.sid == m.sid);
      CHECK(d.source == m.source);
      check_field(m.date_days, d.date_days, 1.0);
      check_field(m.time_of_day_s, d.time_of_day_s, 1e-4);
    }
  }
}

TEST_CASE("n2k: system time from UNIX ns floors to 100 us and round-trips") {
  sonarloop::testing::TestRng rng(0x2002);
  for (int i = 0; i < 2000; ++i) {
    const auto unix_ns = static_cast<std::int64_t>(rng.below(5'000'000'000'000'000'000ull));
    const SystemTime t = system_time_from_unix_ns(unix_ns, 3);
    const auto back = decode<SystemTime>(encode(t, kSource));
    REQUIRE(back);
    const auto ns = unix_ns_from_system_time(*back);
    REQUIRE(ns);
    CHECK(*ns == unix_ns - unix_ns % 100'000);
  }
  CHECK(*system_time_from_unix_ns(-5, 0).date_days == 0.0);
  CHECK_FALSE(unix_ns_from_system_time(SystemTime{}).has_value());
}
