// What a render worker does for one ping: no allocation once warmed up, the same bytes whatever
// the order and whichever renderer, the scene made ahead of the pings, and the navigation
// written into the XTF ping. Allocations are counted by replacing the global operator new for
// this test executable, on the calling thread only.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <new>
#include <numbers>

#include "config/loader/scenario_loader.h"
#include "drivers/xtf/xtf_codec.h"
#include "emulator/ping_producer.h"
#include "emulator/xtf_ping.h"
#include "tests/emulator/test_scenario.h"
#include "tests/support/allocation_counter.h"

using sonarloop::testing::allocations_in;

using namespace sonarloop;
using namespace sonarloop::emulator;

namespace {

// Everything a producer needs, for the small test scenario.
struct Rig {
  config::Scenario sc = config::parse_scenario(testing::small_scenario_yaml(), "test.yaml");
  scene::Scene scene{sc.scene};
  render::SonarSetup setup = render::make_sonar_setup(sc.sonar, sc.scene.water);
  std::unique_ptr<render::PingRenderer> renderer =
      render::make_ping_renderer(render::RendererKind::kProfile, setup);
  vehicle::Trajectory trajectory{sc.vehicle.trajectory};
  vehicle::NavSensorModel nav{sc.vehicle.nav, sc.scene.seed};
  LocalTangentPlane ltp{GeoPoint{sc.scene.origin.latitude_deg, sc.scene.origin.longitude_deg}};
  xtf::XtfFileHeader header = make_xtf_file_header(setup, "test", "");
  MonotonicClock clock;

  PingProducerSetup producer_setup(double prepare_ahead_m = 10.0) {
    PingProducerSetup p;
    p.renderer = renderer.get();
    p.scene = &scene;
    p.trajectory = &trajectory;
    p.nav = &nav;
    p.ltp = &ltp;
    p.header = &header;
    p.clock = &clock;
    p.seed = sc.scene.seed;
    p.ping_period_ns = from_seconds(setup.ping_period_s);
    p.threads = 1;
    p.prepare_ahead_m = prepare_ahead_m;
    return p;
  }
  PingSlot slot() const {
    PingSlot s;
    s.packet.assign(65536, 0);
    return s;
  }
};

}  // namespace

TEST_CASE("ping producer: no allocation per ping once warmed up") {
  Rig rig;
  ScenePingProducer p(rig.producer_setup(1.0));
  p.set_epoch_utc_ns(1'767'225'600'000'000'000);
  p.prepare(0, 1);
  PingSlot slot = rig.slot();
  // warm up: every ping of the window once (its heightmap tiles, and those it prepares ahead)
  for (std::int64_t k = 0; k < 45; ++k)
    p.produce(k, 0, slot);
  CHECK(allocations_in([&] {
          for (std::int64_t k = 5; k < 45; ++k)
            p.produce(k, 0, slot);
        }) == 0);
  CHECK(slot.packet_size > 0);
  CHECK(slot.emitted);
}

TEST_CASE("ping producer: a ping is the same bytes whatever was produced before it") {
  Rig rig;
  ScenePingProducer a(rig.producer_setup());
  ScenePingProducer b(rig.producer_setup());
  a.set_epoch_utc_ns(1'767'225'600'000'000'000);
  b.set_epoch_utc_ns(1'767'225'600'000'000'000);
  PingSlot sa = rig.slot(), sb = rig.slot();
  // a renders 0..40 in order, b renders 40 first
  for (std::int64_t k = 0; k <= 40; ++k)
    a.produce(k, 0, sa);
  b.produce(40, 0, sb);
  REQUIRE(sa.packet_size == sb.packet_size);
  CHECK(std::equal(sa.packet.begin(), sa.packet.begin() + static_cast<long>(sa.packet_size),
                   sb.packet.begin()));
  CHECK(sa.truth.t == 40 * from_seconds(rig.setup.ping_period_s));
}

TEST_CASE("ping producer: workers make the scene ahead of the pings they render") {
  Rig rig;
  ScenePingProducer p(rig.producer_setup(40.0));
  // 40 m of track at 2 m/s and 26.7 ms per ping (further than the tiles ping 0 reads reach)
  CHECK(p.prepare_ahead_pings() ==
        static_cast<std::int64_t>(std::ceil(40.0 / (2.0 * rig.setup.ping_period_s))));
  p.set_epoch_utc_ns(1'767'225'600'000'000'000);
  PingSlot slot = rig.slot();
  p.produce(0, 0, slot);
  const std::uint64_t rendered = rig.scene.seabed().tiles_made();
  REQUIRE(rendered > 0);
  // the work ahead of ping 0 makes the tiles of the ping 40 m ahead: rendering it makes none
  p.work_ahead(0, 0);
  const std::uint64_t made = rig.scene.seabed().tiles_made();
  REQUIRE(made > rendered);
  render::PingScratch scratch;
  render::PingLines lines;
  const Pose ahead =
      rig.trajectory.state_at(p.prepare_ahead_pings() * from_seconds(rig.setup.ping_period_s)).pose;
  rig.renderer->render(rig.scene, ahead, 1, 0, {}, scratch, lines);
  CHECK(rig.scene.seabed().tiles_made() == made);
}

TEST_CASE("ping producer: the ray-traced renderer produces the same packets whatever came first") {
  Rig rig;
  rig.renderer = render::make_ping_renderer(render::RendererKind::kRaytrace, rig.setup);
  ScenePingProducer a(rig.producer_setup());
  ScenePingProducer b(rig.producer_setup());
  a.set_epoch_utc_ns(1'767'225'600'000'000'000);
  b.set_epoch_utc_ns(1'767'225'600'000'000'000);
  PingSlot sa = rig.slot(), sb = rig.slot();
  b.produce(30, 0, sb);
  for (std::int64_t k = 0; k <= 30; k += 10)
    a.produce(k, 0, sa);
  REQUIRE(sa.packet_size == sb.packet_size);
  CHECK(std::equal(sa.packet.begin(), sa.packet.begin() + static_cast<long>(sa.packet_size),
                   sb.packet.begin()));
}

TEST_CASE("ping producer: the XTF ping carries the measured navigation, truth the true pose") {
  Rig rig;
  ScenePingProducer p(rig.producer_setup());
  const std::int64_t epoch = 1'767'225'600'000'000'000;
  p.set_epoch_utc_ns(epoch);
  PingSlot slot = rig.slot();
  const std::int64_t k = 100;
  p.produce(k, 0, slot);
  const SimTime t = k * from_seconds(rig.setup.ping_period_s);
  const auto state = rig.trajectory.state_at(t);
  const auto nav = rig.nav.measure(state);
  const xtf::XtfPing ping = xtf::decode_ping(
      std::span<const std::uint8_t>(slot.packet.data(), slot.packet_size), rig.header);
  const GeoPoint g = rig.ltp.to_geodetic(nav.north_m, nav.east_m);
  CHECK(ping.header.ping_number == k);
  CHECK(ping.header.sensor_y == Approx(g.latitude_deg).margin(1e-12));
  CHECK(ping.header.sensor_x == Approx(g.longitude_deg).margin(1e-12));
  CHECK(ping.header.sensor_heading_deg == Approx(nav.heading * 180 / std::numbers::pi));
  CHECK(ping.channels.size() == 2);
  CHECK(slot.truth.t == t);
  CHECK(slot.truth.time_utc_ns == epoch + t);
  CHECK(slot.truth.pose.position_W.x() == state.pose.position_W.x());
  CHECK_FALSE(slot.truth.external);
  // the error the navigation adds is visible (the scenario has nav noise)
  CHECK(std::abs(nav.north_m - state.pose.position_W.x()) > 0.0);
}
