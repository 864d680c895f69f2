#include "emulator/pose_source.h"

#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "drivers/can/socketcan.h"
#include "drivers/can/socketcand_client.h"
#include "drivers/can/socketcand_server.h"
#include "drivers/n2k/messages.h"
#include "drivers/net/udp_receiver.h"
#include "drivers/net/udp_sender.h"
#include "drivers/pose/pose_message.h"
#include "tests/emulator/pose_source_support.h"
#include "tests/support/skip.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;
using namespace sonarloop::emulator;
using namespace sonarloop::emulator::pose_test;
using Catch::Matchers::Contains;

TEST_CASE("pose source udp: messages update latest(); received_ns is the injected time") {
  const LocalTangentPlane ltp(kOrigin);
  InjectedClock clock;
  auto source = open_pose_source("udp:127.0.0.1:0", ltp, clock.fn());
  auto* udp = dynamic_cast<UdpPoseSource*>(source.get());
  REQUIRE(udp);
  CHECK_THAT(source->describe(), Contains("udp pose on 127.0.0.1:"));
  CHECK_FALSE(source->latest());  // nothing yet
  net::UdpSender tx(net::HostPort{"127.0.0.1", udp->bound_port()});

  clock.value = 1000;
  const PoseMessage m1 = message(1);
  send(tx, m1);
  REQUIRE(wait_until([&] { return udp->stats().updates == 1; }));
  auto p = source->latest();
  REQUIRE(p);
  CHECK(p->received_ns == 1000);
  CHECK(p->has_position);
  CHECK(p->has_depth);
  CHECK(p->has_heading);
  CHECK(p->has_attitude);
  const Vec2 ne = ltp.to_local(GeoPoint{m1.latitude_deg, m1.longitude_deg});
  CHECK(p->pose.position_W.x() == Approx(ne.x()).margin(1e-9));
  CHECK(p->pose.position_W.y() == Approx(ne.y()).margin(1e-9));
  CHECK(p->pose.position_W.x() > 100.0);  // ~ 0.0012345 deg north of the origin
  CHECK(p->pose.position_W.z() == 35.5);
  CHECK(p->altitude_m == 12.25);
  CHECK(p->pose.yaw == 1.5);
  CHECK(p->pose.pitch == -0.02);
  CHECK(p->pose.roll == 0.01);

  // silence: the clock moves on, received_ns does not
  clock.value = 5000;
  let_time_pass();
  p = source->latest();
  REQUIRE(p);
  CHECK(p->received_ns == 1000);
  CHECK(clock.value - p->received_ns == 4000);  // what the emulator compares with its limit

  // the next message: a snapshot without altitude (no bottom lock) and without attitude
  PoseMessage m2 = message(2);
  m2.altitude_m = kNaN;
  m2.pitch_rad = kNaN;
  send(tx, m2);
  REQUIRE(wait_until([&] { return udp->stats().updates == 2; }));
  p = source->latest();
  CHECK(p->received_ns == 5000);
  CHECK(std::isnan(p->altitude_m));
  CHECK_FALSE(p->has_attitude);
  CHECK(p->has_position);
  CHECK(p->pose.position_W.x() > ne.x());  // 1e-6 deg further north

  // a late (older) message is dropped; a gap in the sequence is counted as lost
  clock.value = 6000;
  send(tx, message(1));
  REQUIRE(wait_until([&] { return udp->stats().out_of_order == 1; }));
  CHECK(source->latest()->received_ns == 5000);
  send(tx, message(7));
  REQUIRE(wait_until([&] { return udp->stats().updates == 3; }));
  CHECK(udp->stats().lost == 4);
  CHECK(source->latest()->received_ns == 6000);
  // a jump back by more than the window, or far ahead, is a sender that started again: the
  // message is taken, and nothing is counted as lost (a jump ahead by 2^31 - 1 counted 2.1
  // billion lost before)
  // (the contents of messages 8, 9, 10: plausible in time and place)
  const auto numbered = [](std::uint32_t content, std::uint32_t sequence) {
    PoseMessage m = message(content);
    m.sequence = sequence;
    return m;
  };
  constexpr std::uint32_t kBack = 7u - 80u;  // wraps: 80 behind
  send(tx, numbered(8, kBack));
  REQUIRE(wait_until([&] { return udp->stats().updates == 4; }));
  send(tx, numbered(9, kBack + 0x7fffffffu));
  REQUIRE(wait_until([&] { return udp->stats().updates == 5; }));
  CHECK(udp->stats().sequence_restarts == 2);
  CHECK(udp->stats().lost == 4);
  send(tx, numbered(10, kBack + 0x7fffffffu + 3u));  // then the counting goes on from there
  REQUIRE(wait_until([&] { return udp->stats().updates == 6; }));
  CHECK(udp->stats().lost == 6);

  // malformed datagrams are counted and change nothing
  clock.value = 7000;
  std::vector<std::uint8_t> junk = {'S', 'L', 'P', 'X', 1, 0};
  REQUIRE(tx.send(junk));
  std::vector<std::uint8_t> huge(3000, 0);
  REQUIRE(tx.send(huge));
  REQUIRE(wait_until([&] { return udp->stats().malformed == 2; }));
  CHECK_THAT(udp->stats().last_error, Contains("3000 bytes"));
  CHECK(source->latest()->received_ns == 6000);
  CHECK_THAT(source->describe(),
             Contains("6 updates, 2 malformed") && Contains("6 lost, 2 sender restarts"));
}

TEST_CASE("pose source udp: a port in use is a clear error") {
  const LocalTangentPlane ltp(kOrigin);
  net::UdpReceiver taken(net::HostPort{"127.0.0.1", 0});
  const std::string spec = "udp:127.0.0.1:" + std::to_string(taken.bound_port());
  try {
    open_pose_source(spec, ltp, [] { return std::int64_t{0}; });
    FAIL("no error for a port in use");
  } catch (const std::runtime_error& e) {
    CHECK_THAT(e.what(), Contains("--pose-from " + spec) && Contains("in use"));
  }
}

TEST_CASE("pose source: malformed specs are rejected") {
  const LocalTangentPlane ltp(kOrigin);
  auto now = [] { return std::int64_t{0}; };
  CHECK_THROWS_AS(open_pose_source("gps:/dev/ttyS0", ltp, now), std::invalid_argument);
  CHECK_THROWS_WITH(
      open_pose_source("gps:/dev/ttyS0", ltp, now),
      Contains("can:IFACE, socketcand:HOST:PORT[:CHANNEL], udp:HOST:PORT or imc:udp:HOST:PORT"));
  CHECK_THROWS_AS(open_pose_source("udp:example.org:5700", ltp, now), std::invalid_argument);
  CHECK_THROWS_AS(open_pose_source("socketcand:127.0.0.1", ltp, now), std::invalid_argument);
  CHECK_THROWS_AS(open_pose_source("can:", ltp, now), std::invalid_argument);
  CHECK_THROWS_AS(open_pose_source("udp:127.0.0.1:0", ltp, nullptr), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// NMEA 2000 through socketcand

TEST_CASE("pose source socketcand: N2K frames from our socketcand server update the pose") {
  const LocalTangentPlane ltp(kOrigin);
  InjectedClock clock;
  can::SocketcandServer server(net::HostPort{"127.0.0.1", 0});
  const std::string spec = "socketcand:127.0.0.1:" + std::to_string(server.bound_port()) + ":can0";
  auto source = open_pose_source(spec, ltp, clock.fn());
  auto* src = dynamic_cast<CanPoseSource*>(source.get());
  REQUIRE(src);
  CHECK_THAT(source->describe(), Contains("socketcand pose from 127.0.0.1:") && Contains("(can0)"));
  REQUIRE(wait_until([&] { return server.streaming_clients() == 1; }));

  constexpr std::uint8_t kSa = 0x23;
  const double lat = 59.9123456, lon = 10.7654321;
  const double heading = 2.3456, pitch = -0.0262, roll = 0.0393;
  const double altitude = 12.34, depth = 25.5;
  clock.value = 111;
  server.send(n2k::encode(n2k::PositionRapidUpdate{lat, lon}, kSa), 0);
  REQUIRE(wait_until([&] { return src->stats().updates == 1; }));
  auto p = source->latest();
  REQUIRE(p);
  CHECK(p->received_ns == 111);
  CHECK(p->has_position);
  CHECK_FALSE(p->has_heading);
  CHECK_FALSE(p->has_attitude);
  CHECK_FALSE(p->has_depth);
  CHECK(std::isnan(p->altitude_m));

  clock.value = 222;
  n2k::VesselHeading h;
  h.sid = 7;
  h.heading_rad = heading;
  server.send(n2k::encode(h, kSa), 0);
  n2k::Attitude a;
  a.sid = 7;
  a.yaw_rad = 0.5;  // not used: heading comes from 127250
  a.pitch_rad = pitch;
  a.roll_rad = roll;
  server.send(n2k::encode(a, kSa), 0);
  n2k::WaterDepth w;
  w.sid = 7;
  w.depth_m = altitude;  // water below the transducer
  w.offset_m = depth;    // transducer to surface
  server.send(n2k::encode(w, kSa), 0);
  // frames without pose content: ignored; an 11-bit frame: not NMEA 2000
  n2k::CogSogRapidUpdate cog;
  cog.cog_rad = 1.0;
  cog.sog_mps = 2.0;
  server.send(n2k::encode(cog, kSa), 0);
  can::CanFrame sff;
  sff.id = 0x123;
  sff.extended = false;
  sff.len = 8;
  server.send(sff, 0);
  REQUIRE(wait_until([&] {
    const auto s = src->stats();
    return s.updates == 4 && s.ignored == 1 && s.malformed == 1;
  }));

  p = source->latest();
  REQUIRE(p);
  CHECK(p->received_ns == 222);
  CHECK(p->has_position);
  CHECK(p->has_heading);
  CHECK(p->has_attitude);
  CHECK(p->has_depth);
  // within the PGNs' resolution: 1e-7 deg (~1.1 cm north, 0.6 cm east here), 1e-4 rad, 0.01 m,
  // 0.001 m
  const Vec2 ne = ltp.to_local(GeoPoint{lat, lon});
  CHECK(std::abs(p->pose.position_W.x() - ne.x()) <= 0.5e-7 * 111'300.0);
  CHECK(std::abs(p->pose.position_W.y() - ne.y()) <= 0.5e-7 * 55'800.0);
  CHECK(std::abs(p->pose.yaw - heading) <= 0.5e-4 + 1e-12);
  CHECK(std::abs(p->pose.pitch - pitch) <= 0.5e-4 + 1e-12);
  CHECK(std::abs(p->pose.roll - roll) <= 0.5e-4 + 1e-12);
  CHECK(std::abs(p->altitude_m - altitude) <= 0.005 + 1e-12);
  CHECK(std::abs(p->pose.position_W.z() - depth) <= 0.0005 + 1e-12);
  CHECK_THAT(src->stats().last_error, Contains("00000123"));

  // a magnetic heading is made true with the variation it carries
  clock.value = 333;
  n2k::VesselHeading mag;
  mag.heading_rad = 1.0;
  mag.variation_rad = 0.1;
  mag.reference = n2k::DirectionReference::kMagnetic;
  server.send(n2k::encode(mag, kSa), 0);
  REQUIRE(wait_until([&] { return src->stats().updates == 5; }));
  CHECK(std::abs(source->latest()->pose.yaw - 1.1) <= 1e-4);

  // a vehicle deeper than 128267's Offset can carry: depth unknown, not the last value kept
  n2k::WaterDepth deep;
  deep.depth_m = 7.5;
  server.send(n2k::encode(deep, kSa), 0);
  REQUIRE(wait_until([&] { return src->stats().updates == 6; }));
  CHECK_FALSE(source->latest()->has_depth);
  CHECK(std::abs(source->latest()->altitude_m - 7.5) <= 0.005);

  // silence: received_ns stays at the last receipt while the clock moves on
  clock.value = 999;
  let_time_pass();
  CHECK(source->latest()->received_ns == 333);

  // the server goes away: reported, the last pose is kept, received_ns does not move
  server.stop();
  REQUIRE(wait_until([&] { return !src->connected(); }));
  CHECK(src->stats().receive_errors == 1);
  CHECK_THAT(source->describe(), Contains("disconnected"));
  CHECK(source->latest()->received_ns == 333);
}

TEST_CASE("pose source can: reconnects after the connection is lost") {
  const LocalTangentPlane ltp(kOrigin);
  InjectedClock clock;
  auto first = std::make_unique<can::SocketcandServer>(net::HostPort{"127.0.0.1", 0});
  can::SocketcandServer second(net::HostPort{"127.0.0.1", 0});
  std::atomic<std::uint16_t> port{first->bound_port()};
  std::vector<std::string> warnings;
  std::mutex warnings_mu;
  PoseSourceOptions options;
  options.reconnect_interval_ms = 50;
  options.on_warning = [&](const std::string& w) {
    std::lock_guard lock(warnings_mu);
    warnings.push_back(w);
  };
  CanPoseSource source(
      "test source",
      [&] {
        return std::make_unique<can::SocketcandClient>(net::HostPort{"127.0.0.1", port});
      },
      ltp, clock.fn(), options);
  REQUIRE(wait_until([&] { return first->streaming_clients() == 1; }));
  clock.value = 10;
  first->send(n2k::encode(n2k::PositionRapidUpdate{59.9, 10.75}, 1), 0);
  REQUIRE(wait_until([&] { return source.stats().updates == 1; }));

  port = second.bound_port();
  first.reset();  // connection lost; the source reconnects to `second`
  REQUIRE(wait_until([&] { return second.streaming_clients() == 1; }));
  // 111 m further north 20 s later: within a vehicle's reach (a jump would be rejected)
  clock.value = 20'000'000'000;
  second.send(n2k::encode(n2k::PositionRapidUpdate{59.901, 10.75}, 1), 0);
  REQUIRE(wait_until([&] { return source.stats().updates == 2; }));
  CHECK(source.latest()->received_ns == 20'000'000'000);
  CHECK(source.latest()->pose.position_W.x() ==
        Approx(ltp.to_local({59.901, 10.75}).x()).margin(0.02));
  CHECK(source.stats().reconnects == 1);
  CHECK(source.connected());
  std::lock_guard lock(warnings_mu);
  REQUIRE(warnings.size() >= 2);
  CHECK_THAT(warnings.front(), Contains("test source: receive failed"));
  CHECK_THAT(warnings.back(), Contains("reconnected"));
}

TEST_CASE("pose source socketcand: a refused connection is a clear error") {
  const LocalTangentPlane ltp(kOrigin);
  std::uint16_t port = 0;
  {
    can::SocketcandServer probe(net::HostPort{"127.0.0.1", 0});
    port = probe.bound_port();
  }
  const std::string spec = "socketcand:127.0.0.1:" + std::to_string(port);
  CHECK_THROWS_WITH(open_pose_source(spec, ltp, [] { return std::int64_t{0}; }),
                    Contains("--pose-from " + spec));
}

// ---------------------------------------------------------------------------------------------
// SocketCAN

TEST_CASE("pose source can: N2K frames from a SocketCAN interface (vcan0)", "[may_skip]") {
  const LocalTangentPlane ltp(kOrigin);
  InjectedClock clock;
  std::string reason;
  if (!can::SocketCanTransport::kernel_supports_can(&reason)) {
    // here the spec fails with a message that says why and what to use instead
    REQUIRE_THROWS_WITH(open_pose_source("can:vcan0", ltp, clock.fn()),
                        Contains("--pose-from can:vcan0"));
    testing::skip_test("socket(AF_CAN) does not work on this kernel (" + reason +
                       "); use socketcand:HOST:PORT");
  }
  std::unique_ptr<PoseSource> source;
  try {
    source = open_pose_source("can:vcan0", ltp, clock.fn());
  } catch (const std::runtime_error& e) {
    testing::skip_test(std::string("no vcan0 interface (") + e.what() + ")");
  }
  can::SocketCanTransport bus("vcan0");
  clock.value = 42;
  bus.send(n2k::encode(n2k::PositionRapidUpdate{59.9123456, 10.7654321}, 0x23), 0);
  REQUIRE(wait_until([&] { return source->latest().has_value(); }));
  CHECK(source->latest()->received_ns == 42);
  CHECK(source->latest()->has_position);
}

TEST_CASE("pose source udp: tools/send_pose.py (the documented usage example) drives it") {
  const LocalTangentPlane ltp(kOrigin);
  InjectedClock clock;
  clock.value = 77;
  UdpPoseSource source(net::HostPort{"127.0.0.1", 0}, ltp, clock.fn());
  const std::string cmd = std::string(SONARLOOP_PYTHON) + " " + SONARLOOP_SOURCE_DIR +
                          "/tools/send_pose.py 127.0.0.1:" + std::to_string(source.bound_port()) +
                          " --lat 59.901 --lon 10.752 --depth 20 --altitude 8 --heading-deg 90"
                          " --pitch-deg 2 --count 3 --rate 100 2> /dev/null";
  REQUIRE(sonarloop::testing::run_command(cmd) == 0);
  REQUIRE(wait_until([&] { return source.stats().updates == 3; }));
  const auto p = source.latest();
  REQUIRE(p);
  CHECK(p->received_ns == 77);
  CHECK(source.stats().lost == 0);
  const Vec2 ne = ltp.to_local(GeoPoint{59.901, 10.752});
  CHECK(p->pose.position_W.x() == Approx(ne.x()).margin(1e-6));  // speed 0: stays put
  CHECK(p->pose.position_W.y() == Approx(ne.y()).margin(1e-6));
  CHECK(p->pose.position_W.z() == 20.0);
  CHECK(p->altitude_m == 8.0);
  CHECK(p->pose.yaw == Approx(std::numbers::pi / 2));
  CHECK(p->pose.pitch == Approx(2.0 * std::numbers::pi / 180.0));
  CHECK(p->pose.roll == 0.0);
}
