#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <numbers>

#include "drivers/n2k/messages.h"
#include "emulator/nav_frames.h"

using namespace sonarloop;
using namespace sonarloop::emulator;

TEST_CASE("nav frames: kPositionPgnBit is 129025's bit, sampled every 100 ms") {
  CHECK(kNavPgns[0].pgn == 129025u);
  CHECK(kPositionPgnBit == 1u);
  CHECK(kNavPgns[0].period_ns == 100'000'000);
}

TEST_CASE("NavSchedule: each PGN at its standard rate, one sample per instant") {
  NavSchedule s;
  std::map<std::uint32_t, int> count;
  int samples = 0;
  SimTime last = -1;
  while (s.next_time() < 10 * kNanosecondsPerSecond) {
    const auto sample = s.pop(s.next_time());
    CHECK(sample.t > last);  // strictly increasing instants
    CHECK(sample.skipped == 0);
    last = sample.t;
    ++samples;
    for (int i = 0; i < kNavPgnCount; ++i) {
      if (sample.due & (1u << i)) {
        ++count[kNavPgns[static_cast<std::size_t>(i)].pgn];
        CHECK(sample.t % kNavPgns[static_cast<std::size_t>(i)].period_ns == 0);
      }
    }
  }
  CHECK(count[129025] == 100);
  CHECK(count[127250] == 100);
  CHECK(count[127251] == 100);
  CHECK(count[129026] == 40);
  CHECK(count[127257] == 10);
  CHECK(count[128259] == 10);
  CHECK(count[128267] == 10);
  CHECK(count[126992] == 10);
  // 100 ms grid + the 250 ms instants that are not on it (250, 750, ... ms)
  CHECK(samples == 120);
}

TEST_CASE("NavSchedule: after an overrun each PGN resyncs on its own grid") {
  NavSchedule s;
  s.pop(0);  // everything at t = 0
  // the publisher stalls until 1.05 s. Each overdue PGN publishes its one overdue sample (late),
  // then skips the ticks that passed during the stall and resumes on its grid
  const SimTime now = 1'050'000'000;
  auto a = s.pop(now);
  CHECK(a.t == 100'000'000);
  CHECK(a.skipped == 3 * 9);  // 3 PGNs at 100 ms skip 200..1000 ms
  auto b = s.pop(now);
  CHECK(b.t == 250'000'000);
  CHECK(b.skipped == 3);  // 500, 750, 1000 ms
  auto c = s.pop(now);
  CHECK(c.t == 1'000'000'000);  // the 1 s PGNs were due at 1 s: late, none skipped
  CHECK(c.skipped == 0);
  // then on time again, on the original grids
  CHECK(s.next_time() == 1'100'000'000);
  auto d = s.pop(1'100'000'000);
  CHECK(d.skipped == 0);
  CHECK(s.next_time() == 1'200'000'000);
  s.pop(1'200'000'000);
  CHECK(s.next_time() == 1'250'000'000);
}

TEST_CASE("make_nav_frames: the solution's values round-trip within the PGN resolution") {
  const LocalTangentPlane ltp(GeoPoint{55.9, -3.2});
  vehicle::NavSolution nav;
  nav.t = 3'400'000'000;
  nav.north_m = 123.456;
  nav.east_m = -78.9;
  nav.depth_m = 17.43;
  nav.heading = 3.5;  // > π: Attitude's yaw is wrapped to ±π
  nav.pitch = -0.031;
  nav.roll = 0.012;
  nav.speed_over_ground_m_s = 2.013;
  nav.course_over_ground = 0.02;
  nav.yaw_rate = -0.0123;
  nav.altitude_m = 7.52;
  const std::int64_t utc = 1'767'225'603'400'000'000;
  std::array<can::CanFrame, kNavPgnCount> frames{};
  const std::size_t n = make_nav_frames(nav, ltp, utc, 17, kAllNavPgns, frames);
  REQUIRE(n == 8);
  const GeoPoint g = ltp.to_geodetic(nav.north_m, nav.east_m);
  for (std::size_t i = 0; i < n; ++i) {
    CHECK((frames[i].id & 0xFF) == kNavSourceAddress);
    const auto any = n2k::decode_any(frames[i]);
    REQUIRE(any.has_value());
    std::visit(
        [&](const auto& m) {
          using T = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<T, n2k::PositionRapidUpdate>) {
            CHECK(*m.latitude_deg == Approx(g.latitude_deg).margin(0.6e-7));
            CHECK(*m.longitude_deg == Approx(g.longitude_deg).margin(0.6e-7));
          } else if constexpr (std::is_same_v<T, n2k::VesselHeading>) {
            CHECK(m.sid == 17);
            CHECK(*m.heading_rad == Approx(3.5).margin(0.6e-4));
            CHECK_FALSE(m.deviation_rad.has_value());
          } else if constexpr (std::is_same_v<T, n2k::RateOfTurn>) {
            CHECK(*m.rate_rad_per_s == Approx(-0.0123).margin(3.2e-8));
          } else if constexpr (std::is_same_v<T, n2k::CogSogRapidUpdate>) {
            CHECK(*m.cog_rad == Approx(0.02).margin(0.6e-4));
            CHECK(*m.sog_mps == Approx(2.013).margin(0.006));
          } else if constexpr (std::is_same_v<T, n2k::Attitude>) {
            CHECK(*m.yaw_rad == Approx(3.5 - 2 * std::numbers::pi).margin(0.6e-4));
            CHECK(*m.pitch_rad == Approx(-0.031).margin(0.6e-4));
            CHECK(*m.roll_rad == Approx(0.012).margin(0.6e-4));
          } else if constexpr (std::is_same_v<T, n2k::SpeedWaterReferenced>) {
            CHECK(*m.speed_water_mps == Approx(2.013).margin(0.006));
            CHECK(m.speed_water_type == n2k::WaterReference::kDoppler);
          } else if constexpr (std::is_same_v<T, n2k::WaterDepth>) {
            CHECK(*m.depth_m == Approx(7.52).margin(0.006));
            CHECK(*m.offset_m == Approx(17.43).margin(0.0006));
          } else if constexpr (std::is_same_v<T, n2k::SystemTime>) {
            CHECK(*n2k::unix_ns_from_system_time(m) == utc);
          }
        },
        *any);
  }
}

TEST_CASE("make_nav_frames: only the due PGNs; unknown values are 'not available'") {
  const LocalTangentPlane ltp(GeoPoint{0.0, 0.0});
  vehicle::NavSolution nav;
  nav.altitude_m = std::nan("");
  nav.depth_m = 40.0;  // deeper than 128267's Offset field can say
  std::array<can::CanFrame, kNavPgnCount> frames{};
  // water depth only
  NavPgnMask depth_only = 0;
  for (int i = 0; i < kNavPgnCount; ++i)
    if (kNavPgns[static_cast<std::size_t>(i)].pgn == 128267) depth_only = 1u << i;
  REQUIRE(make_nav_frames(nav, ltp, 0, 3, depth_only, frames) == 1);
  const auto d = n2k::decode<n2k::WaterDepth>(frames[0]);
  REQUIRE(d.has_value());
  CHECK_FALSE(d->depth_m.has_value());
  CHECK_FALSE(d->offset_m.has_value());
  // a stale external pose: only System Time goes out
  REQUIRE(make_nav_frames(nav, ltp, 0, 3, kAllNavPgns & pose_free_pgns(), frames) == 1);
  CHECK(n2k::decode<n2k::SystemTime>(frames[0]).has_value());
  std::array<can::CanFrame, 4> small{};
  CHECK_THROWS_AS(make_nav_frames(nav, ltp, 0, 3, kAllNavPgns, small), std::invalid_argument);
}
