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
#include "emulator/pose_message.h"
#include "tests/support/skip.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;
using namespace sonarloop::emulator;
using Catch::Matchers::Contains;

namespace {

const GeoPoint kOrigin{59.9, 10.75};
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The injected clock: tests set the value that the source reads at each receipt.
struct InjectedClock {
  std::atomic<std::int64_t> value{0};
  std::atomic<int> calls{0};
  std::function<std::int64_t()> fn() {
    return [this] {
      ++calls;
      return value.load();
    };
  }
};

// Polls `done` every 5 ms for up to 20 s (a bound against hangs, not a timing assertion).
bool wait_until(const std::function<bool()>& done) {
  for (int i = 0; i < 4000; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

// Lets a silent source's thread run through several receive timeouts.
void let_time_pass() {
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
}

PoseMessage message(std::uint32_t seq) {
  PoseMessage m;
  m.sequence = seq;
  m.time_unix_ns = 1'767'225'600'000'000'000 + static_cast<std::int64_t>(seq) * 100'000'000;
  m.latitude_deg = 59.9012345 + 1e-6 * seq;
  m.longitude_deg = 10.7523456;
  m.depth_m = 35.5;
  m.altitude_m = 12.25;
  m.heading_rad = 1.5;
  m.pitch_rad = -0.02;
  m.roll_rad = 0.01;
  return m;
}

void send(net::UdpSender& tx, const PoseMessage& m) {
  const auto bytes = encode_pose_message(m);
  REQUIRE(tx.send(bytes));
}

// The example datagram of emulator/pose_message.md.
const std::vector<std::uint8_t> kExampleDatagram = {
    0x53, 0x4C, 0x50, 0x4D, 0x01, 0x00, 0x50, 0x00, 0x2A, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x15, 0xCD, 0x55, 0xF5, 0x51, 0x72, 0x86, 0x18, 0x23, 0x53, 0x99, 0xBD, 0xC7, 0xF4, 0x4D, 0x40,
    0x01, 0x9E, 0x59, 0xB7, 0xE6, 0x87, 0x25, 0x40, 0x00, 0x00, 0x00, 0x00, 0x00, 0xC0, 0x41, 0x40,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x28, 0x40, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xF8, 0x3F,
    0x7B, 0x14, 0xAE, 0x47, 0xE1, 0x7A, 0x94, 0xBF, 0x7B, 0x14, 0xAE, 0x47, 0xE1, 0x7A, 0x84, 0x3F};

}  // namespace

// ---------------------------------------------------------------------------------------------
// the pose message

TEST_CASE("pose message: the documented example encodes and decodes byte for byte") {
  PoseMessage m;
  m.sequence = 42;
  m.time_unix_ns = 1'767'225'600'123'456'789;  // 2026-01-01T00:00:00.123456789Z
  m.latitude_deg = 59.9123456;
  m.longitude_deg = 10.7654321;
  m.depth_m = 35.5;
  m.altitude_m = 12.25;
  m.heading_rad = 1.5;
  m.pitch_rad = -0.02;
  m.roll_rad = 0.01;
  const auto bytes = encode_pose_message(m);
  CHECK(std::vector<std::uint8_t>(bytes.begin(), bytes.end()) == kExampleDatagram);
  std::string error;
  const auto d = decode_pose_message(kExampleDatagram, error);
  REQUIRE(d);
  CHECK(d->sequence == 42);
  CHECK(d->time_unix_ns == m.time_unix_ns);
  CHECK(d->latitude_deg == m.latitude_deg);
  CHECK(d->longitude_deg == m.longitude_deg);
  CHECK(d->depth_m == 35.5);
  CHECK(d->altitude_m == 12.25);
  CHECK(d->heading_rad == 1.5);
  CHECK(d->pitch_rad == -0.02);
  CHECK(d->roll_rad == 0.01);
  // NaN = not available survives the round trip
  PoseMessage empty;
  const auto e = decode_pose_message(encode_pose_message(empty), error);
  REQUIRE(e);
  CHECK(std::isnan(e->latitude_deg));
  CHECK(std::isnan(e->roll_rad));
}

TEST_CASE("pose message: malformed datagrams are rejected with a reason") {
  std::string error;
  auto bad = [&](std::vector<std::uint8_t> bytes) {
    error.clear();
    return !decode_pose_message(bytes, error).has_value();
  };
  auto with = [](auto&& edit) {
    PoseMessage m = message(1);
    edit(m);
    const auto b = encode_pose_message(m);
    return std::vector<std::uint8_t>(b.begin(), b.end());
  };
  std::vector<std::uint8_t> v = kExampleDatagram;
  v.pop_back();
  CHECK(bad(v));
  CHECK_THAT(error, Contains("79 bytes, expected 80"));
  v = kExampleDatagram;
  v[3] = 'X';
  CHECK(bad(v));
  CHECK_THAT(error, Contains("bad magic 53 4C 50 58"));
  v = kExampleDatagram;
  v[4] = 2;
  CHECK(bad(v));
  CHECK_THAT(error, Contains("version 2 is not supported"));
  v = kExampleDatagram;
  v[6] = 81;
  CHECK(bad(v));
  CHECK_THAT(error, Contains("size field 81"));
  CHECK(bad(with([](PoseMessage& m) { m.latitude_deg = 91.0; })));
  CHECK_THAT(error, Contains("outside"));
  CHECK(bad(with([](PoseMessage& m) { m.longitude_deg = kNaN; })));
  CHECK_THAT(error, Contains("only one of latitude and longitude"));
  CHECK(bad(with([](PoseMessage& m) { m.depth_m = std::numeric_limits<double>::infinity(); })));
  CHECK(bad(with([](PoseMessage& m) { m.heading_rad = 90.0; })));  // degrees by mistake
  CHECK_THAT(error, Contains("radians"));
  CHECK_FALSE(bad(with([](PoseMessage& m) { m.heading_rad = -0.5; })));
}

// ---------------------------------------------------------------------------------------------
// UDP source

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

  // malformed datagrams are counted and change nothing
  clock.value = 7000;
  std::vector<std::uint8_t> junk = {'S', 'L', 'P', 'X', 1, 0};
  REQUIRE(tx.send(junk));
  std::vector<std::uint8_t> huge(3000, 0);
  REQUIRE(tx.send(huge));
  REQUIRE(wait_until([&] { return udp->stats().malformed == 2; }));
  CHECK_THAT(udp->stats().last_error, Contains("3000 bytes"));
  CHECK(source->latest()->received_ns == 6000);
  CHECK_THAT(source->describe(), Contains("3 updates, 2 malformed"));
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
  CHECK_THROWS_WITH(open_pose_source("gps:/dev/ttyS0", ltp, now),
                    Contains("can:IFACE, socketcand:HOST:PORT[:CHANNEL] or udp:HOST:PORT"));
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

// ---------------------------------------------------------------------------------------------
// implausible poses (docs: pose_source.h "Plausibility")

namespace {

// A UDP source with the limits of a 50 m deep scene whose warnings are collected.
struct CheckedUdpSource {
  InjectedClock clock;
  std::mutex mu;
  std::vector<std::string> warnings;
  std::unique_ptr<UdpPoseSource> source;
  std::unique_ptr<net::UdpSender> tx;

  explicit CheckedUdpSource(const LocalTangentPlane& ltp) {
    PoseSourceOptions options;
    options.limits.max_depth_m = 50.0;
    options.limits.max_altitude_m = 51.0;
    options.on_warning = [this](const std::string& w) {
      std::lock_guard lock(mu);
      warnings.push_back(w);
    };
    source =
        std::make_unique<UdpPoseSource>(net::HostPort{"127.0.0.1", 0}, ltp, clock.fn(), options);
    tx = std::make_unique<net::UdpSender>(net::HostPort{"127.0.0.1", source->bound_port()});
  }
  // Sends `m` and waits until it is accepted or rejected.
  void deliver(const PoseMessage& m) {
    const auto before = source->stats();
    send(*tx, m);
    REQUIRE(wait_until([&] {
      const auto s = source->stats();
      return s.updates + s.rejected > before.updates + before.rejected;
    }));
  }
  std::vector<std::string> warnings_now() {
    std::lock_guard lock(mu);
    return warnings;
  }
};

// message(seq) without its time stamp: samples placed at their arrival (the injected clock)
PoseMessage unstamped(std::uint32_t seq) {
  PoseMessage m = message(seq);
  m.time_unix_ns = 0;
  return m;
}

constexpr std::int64_t kSecond = 1'000'000'000;

}  // namespace

TEST_CASE("pose source udp: absurd depth, altitude and attitude are rejected, counted, warned") {
  const LocalTangentPlane ltp(kOrigin);
  CheckedUdpSource c(ltp);
  c.clock.value = 1 * kSecond;
  c.deliver(unstamped(1));
  REQUIRE(c.source->stats().updates == 1);

  // each one absurd in one way; the clock does not move: one warning line for all
  std::vector<std::pair<std::function<void(PoseMessage&)>, std::string>> absurd = {
      {[](PoseMessage& m) { m.depth_m = -5.0; }, "above the sea surface"},
      {[](PoseMessage& m) { m.depth_m = 1e6; }, "below the scene's deepest seabed (50.0 m)"},
      {[](PoseMessage& m) { m.altitude_m = -0.5; }, "below the seabed"},
      {[](PoseMessage& m) { m.altitude_m = 4000.0; }, "more than the scene's water column"},
      {[](PoseMessage& m) { m.pitch_rad = 1.6; }, "beyond +-90"},
      {[](PoseMessage& m) { m.roll_rad = -std::numbers::pi; }, "beyond +-90"},
  };
  std::uint32_t seq = 2;
  for (const auto& [edit, reason] : absurd) {
    PoseMessage m = unstamped(seq++);
    edit(m);
    c.deliver(m);
    CHECK_THAT(c.source->stats().last_error, Contains(reason));
  }
  auto s = c.source->stats();
  CHECK(s.rejected == absurd.size());
  CHECK(s.updates == 1);
  CHECK(s.malformed == 0);
  CHECK(s.lost == 0);  // rejected messages were received, not lost
  // nothing of them reached the pose: its time and depth are the first message's
  CHECK(c.source->latest()->received_ns == 1 * kSecond);
  CHECK(c.source->latest()->pose.position_W.z() == 35.5);
  auto w = c.warnings_now();
  REQUIRE(w.size() == 1);
  CHECK_THAT(w[0], Contains("udp pose on 127.0.0.1:") &&
                       Contains("implausible pose rejected: pose message 2: depth -5 m"));

  // a second later the next rejection is warned about again, with the count in between
  c.clock.value = 2 * kSecond;
  PoseMessage deep = unstamped(seq++);
  deep.depth_m = 60.0;
  c.deliver(deep);
  w = c.warnings_now();
  REQUIRE(w.size() == 2);
  CHECK_THAT(w[1], Contains("depth 60 m") && Contains("(and 5 more since the last such warning)"));
  CHECK_THAT(c.source->describe(), Contains("7 rejected as implausible"));

  // NaN is "not available" (not absurd): accepted, the part then unknown; a surfaced vehicle
  // 0.5 m "above" the surface in a wave is the surface
  PoseMessage partial = unstamped(seq++);
  partial.depth_m = kNaN;
  partial.pitch_rad = kNaN;
  c.deliver(partial);
  PoseMessage surfaced = unstamped(seq++);
  surfaced.depth_m = -0.5;
  c.deliver(surfaced);
  s = c.source->stats();
  CHECK(s.updates == 3);
  CHECK(s.rejected == 7);
  CHECK(c.source->latest()->pose.position_W.z() == -0.5);
}

TEST_CASE("pose source udp: a position jump faster than a vehicle is rejected until it persists") {
  const LocalTangentPlane ltp(kOrigin);
  CheckedUdpSource c(ltp);
  auto at = [&](std::uint32_t seq, double north_m) {
    PoseMessage m = unstamped(seq);
    const GeoPoint g = ltp.to_geodetic(north_m, 0.0);
    m.latitude_deg = g.latitude_deg;
    m.longitude_deg = g.longitude_deg;
    return m;
  };
  c.clock.value = 10 * kSecond;
  c.deliver(at(1, 0.0));
  // 2 m in 0.1 s (20 m/s, the vehicle speed limit, plus 5 m for a navigation fix): plausible
  c.clock.value += kSecond / 10;
  c.deliver(at(2, 2.0));
  REQUIRE(c.source->stats().updates == 2);
  // 1 km in 0.1 s: a glitch, rejected; the pose stays where it was
  c.clock.value += kSecond / 10;
  c.deliver(at(3, 1000.0));
  CHECK(c.source->stats().rejected == 1);
  CHECK_THAT(c.source->stats().last_error, Contains("position jumped 998 m in 0.100 s"));
  CHECK(c.source->latest()->pose.position_W.x() == Approx(2.0).margin(1e-6));
  // the next fix is back on the track: accepted, and the rejection count starts again
  c.clock.value += kSecond / 10;
  c.deliver(at(4, 2.5));
  CHECK(c.source->stats().updates == 3);
  // a real relocation: rejected reanchor_after - 1 times, then taken as the new position
  const int n = PoseLimits{}.reanchor_after;
  for (int i = 0; i < n; ++i) {
    c.clock.value += kSecond / 10;
    c.deliver(at(static_cast<std::uint32_t>(5 + i), 500.0 + 0.2 * i));
  }
  const auto s = c.source->stats();
  CHECK(s.rejected == 1 + static_cast<std::uint64_t>(n - 1));
  CHECK(s.reanchors == 1);
  CHECK(c.source->latest()->pose.position_W.x() == Approx(500.0 + 0.2 * (n - 1)).margin(1e-6));
  // no interpolation across the jump: just after it, the new position (not a blend with 2.5 m)
  const auto p = c.source->pose_at(c.clock.value - kSecond / 20, kSecond);
  CHECK(p->pose.position_W.x() == Approx(500.0 + 0.2 * (n - 1)).margin(1e-6));
  const auto w = c.warnings_now();
  REQUIRE(!w.empty());
  CHECK_THAT(w.back(), Contains("accepted as the new position after 5 such fixes in a row"));
}

TEST_CASE("pose source udp: time stamps going back or jumping ahead are rejected") {
  const LocalTangentPlane ltp(kOrigin);
  CheckedUdpSource c(ltp);
  const std::int64_t stamp0 = 1'767'225'600'000'000'000;
  auto stamped = [&](std::uint32_t seq, std::int64_t stamp, double north_m) {
    PoseMessage m = message(seq);
    m.time_unix_ns = stamp;
    const GeoPoint g = ltp.to_geodetic(north_m, 0.0);
    m.latitude_deg = g.latitude_deg;
    m.longitude_deg = g.longitude_deg;
    return m;
  };
  c.clock.value = 100 * kSecond;
  c.deliver(stamped(1, stamp0, 0.0));
  c.clock.value += kSecond / 10;
  c.deliver(stamped(2, stamp0 + kSecond / 10, 0.2));
  // 10 s back in time (sequence going on): rejected
  c.clock.value += kSecond / 10;
  c.deliver(stamped(3, stamp0 - 10 * kSecond, 0.4));
  CHECK_THAT(c.source->stats().last_error, Contains("time stamp went back 10.1 s"));
  // an hour ahead in 0.2 s of arrivals: rejected. (Before this check one such stamp moved the
  // stamp-to-clock offset by an hour, and every later sample was placed an hour in the past
  // and dropped from the history: the pose froze while the source looked fresh.)
  c.clock.value += kSecond / 10;
  c.deliver(stamped(4, stamp0 + 3600 * kSecond, 0.6));
  CHECK_THAT(c.source->stats().last_error, Contains("time stamp jumped ahead 3599.9 s"));
  CHECK(c.source->stats().rejected == 2);
  // the sender's next sample is placed on the clock and read back from the history
  c.clock.value += kSecond / 10;
  c.deliver(stamped(5, stamp0 + 4 * kSecond / 10, 0.8));
  CHECK(c.source->stats().updates == 3);
  const auto p = c.source->pose_at(c.clock.value, 0);
  REQUIRE(p);
  CHECK(p->pose.position_W.x() == Approx(0.8).margin(1e-6));
  // a clock really stepped (by an hour) is followed after reanchor_after messages
  const int n = PoseLimits{}.reanchor_after;
  for (int i = 0; i < n; ++i) {
    c.clock.value += kSecond / 10;
    c.deliver(stamped(static_cast<std::uint32_t>(6 + i), stamp0 + (3600 + i) * kSecond, 1.0));
  }
  CHECK(c.source->stats().reanchors == 1);
  CHECK(c.source->stats().rejected == 2 + static_cast<std::uint64_t>(n - 1));
  CHECK(c.source->latest()->received_ns == c.clock.value);
}

TEST_CASE("pose source: pose_limits_for_scene bounds depth by the scene's deepest seabed") {
  scene::SceneDesc sc;
  sc.water.depth_m = 30.0;
  sc.seabed.origin_m = Vec2(-50.0, -50.0);
  sc.seabed.extent_m = Vec2(100.0, 100.0);
  sc.seabed.elevation.slope = Vec2(0.01, 0.0);  // rising 1 cm per metre north
  sc.seabed.elevation.rms_m = 0.5;
  const PoseLimits l = pose_limits_for_scene(sc);
  // deepest at the south edge: 30 + 0.01 x 50 + 6 x 0.5
  CHECK(l.max_depth_m == Approx(33.5));
  CHECK(l.max_altitude_m == Approx(34.5));
  CHECK(l.max_speed_m_s == 20.0);  // the vehicle's speed limit (vehicle_desc.cpp)
  CHECK(l.max_pitch_rad == Approx(std::numbers::pi / 2));
}

TEST_CASE("pose merger: implausible NMEA 2000 attitude, depth and position jumps are rejected") {
  const LocalTangentPlane ltp(kOrigin);
  std::int64_t now = 0;
  PoseLimits limits;
  limits.max_depth_m = 30.0;
  limits.max_altitude_m = 31.0;
  std::vector<std::string> warnings;
  PoseMerger merger(
      ltp, [&] { return now; }, limits, [&](const std::string& w) { warnings.push_back(w); });
  n2k::Attitude a;
  a.pitch_rad = 0.1;
  a.roll_rad = 1.7;  // beyond 90 degrees
  CHECK_FALSE(merger.merge_n2k(n2k::encode(a, 1)));
  n2k::WaterDepth w;
  w.depth_m = 5.0;
  w.offset_m = 31.5;  // deeper than the seabed
  CHECK_FALSE(merger.merge_n2k(n2k::encode(w, 1)));
  CHECK(merger.merge_n2k(n2k::encode(n2k::PositionRapidUpdate{59.9, 10.75}, 1)));
  now += kSecond;
  CHECK_FALSE(merger.merge_n2k(n2k::encode(n2k::PositionRapidUpdate{59.91, 10.75}, 1)));  // 1.1 km
  const auto s = merger.stats();
  CHECK(s.rejected == 3);
  CHECK(s.updates == 1);
  CHECK_THAT(s.last_error, Contains("129025 Position: position jumped"));
  REQUIRE(warnings.size() == 2);  // the third within a second of the first: counted, not said
  CHECK_THAT(warnings[0], Contains("127257 Attitude: pitch 5.7 / roll 97.4 degrees"));
  CHECK_THAT(warnings[1], Contains("(and 1 more since the last such warning)"));
}
