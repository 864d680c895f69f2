// IMC over UDP (emulator/imc_device.h, the pose input's imc:udp source): the device alone (what
// each event sends, in which order, with which values), a whole run at --rate max read back
// from a real socket on 127.0.0.1 with the project's decoder and compared with the run's own
// recording, and an EstimatedState sent to the pose input.
#include <atomic>
#include <catch2/catch.hpp>
#include <cmath>
#include <mutex>
#include <thread>
#include <vector>

#include "common/geodesy.h"
#include "config/loader/scenario_loader.h"
#include "drivers/imc/imc_codec.h"
#include "drivers/net/udp_receiver.h"
#include "drivers/net/udp_sender.h"
#include "drivers/xtf/xtf_file.h"
#include "emulator/emulator.h"
#include "emulator/imc_device.h"
#include "emulator/pose_source.h"
#include "tests/emulator/pose_source_support.h"
#include "tests/emulator/test_scenario.h"
#include "tests/support/temp_dir.h"
#include "units/angles.h"

using namespace sonarloop;
using namespace sonarloop::emulator;

namespace {

// Every datagram waiting on `rx`, decoded (a packet that does not decode fails the test).
std::vector<imc::Packet> drain_imc(net::UdpReceiver& rx, int quiet_ms = 200) {
  std::vector<imc::Packet> out;
  std::vector<std::uint8_t> buf(70000);
  while (const auto d = rx.receive(buf, quiet_ms)) {
    imc::Packet p;
    const imc::DecodeStatus s =
        imc::decode(std::span<const std::uint8_t>(buf.data(), d->datagram_size), p);
    INFO(imc::decode_status_name(s));
    REQUIRE(s == imc::DecodeStatus::kOk);
    out.push_back(std::move(p));
  }
  return out;
}

std::vector<std::uint16_t> ids_of(const std::vector<imc::Packet>& ps) {
  std::vector<std::uint16_t> ids;
  for (const auto& p : ps)
    ids.push_back(p.mgid);
  return ids;
}

// A two-channel ping of 16-bit samples, port and starboard as stored (port far range first).
PingSlot sidescan_slot(SimTime t, std::int64_t utc_ns) {
  PingSlot s;
  s.truth.t = t;
  s.truth.time_utc_ns = utc_ns;
  s.xtf.channels.resize(2);
  s.xtf.channels[0].samples = std::vector<std::uint16_t>{0x0102, 0x0304, 0x0506};
  s.xtf.channels[1].samples = std::vector<std::uint16_t>{0x0A0B, 0x0C0D, 0x0E0F};
  return s;
}

const GeoPoint kImcOrigin{59.9, 10.75};
constexpr std::int64_t kEpochNs = 1'767'225'600'000'000'000;

}  // namespace

TEST_CASE(
    "imc device: Announce and Heartbeat first, SonarData per ping, EstimatedState per "
    "navigation sample") {
  net::UdpReceiver rx(net::HostPort{"127.0.0.1", 0});
  ImcDeviceOptions o;
  o.destination = net::HostPort{"127.0.0.1", rx.bound_port()};
  o.system_name = "auv-test";
  o.services = "imc+udp://127.0.0.1:6002/";
  const LocalTangentPlane ltp(kImcOrigin);
  ImcDevice dev(o, ltp, ImcSonarInfo{600e3, 50.0});
  CHECK(dev.on_wire());
  const SimTime s = kNanosecondsPerSecond;

  dev.ping(sidescan_slot(0, kEpochNs), {});
  vehicle::NavSolution nav;
  nav.t = s / 10;
  nav.north_m = 12.0;
  nav.east_m = -3.0;
  nav.depth_m = 14.0;
  nav.heading = 1.5 * std::numbers::pi;  // west: psi -pi/2
  nav.pitch = 0.02;
  nav.roll = -0.01;
  nav.speed_over_ground_m_s = 2.0;
  nav.course_over_ground = 1.5 * std::numbers::pi;
  nav.yaw_rate = 0.05;
  nav.altitude_m = std::numeric_limits<double>::quiet_NaN();
  dev.nav_solution(nav, kEpochNs + s / 10);
  dev.ping(sidescan_slot(s / 2, kEpochNs + s / 2), {});
  dev.ping(sidescan_slot(s, kEpochNs + s), {});  // a second since the Heartbeat: another one

  const std::vector<imc::Packet> got = drain_imc(rx);
  CHECK(ids_of(got) == std::vector<std::uint16_t>{151, 150, 276, 350, 276, 150, 276});
  for (const auto& p : got) {
    CHECK(p.header.src == imc::kDefaultImcSystem);
    CHECK(p.header.dst == imc::kAnyAddress);
  }
  const auto& announce = std::get<imc::Announce>(got[0].message);
  CHECK(announce.sys_name == "auv-test");
  CHECK(announce.sys_type == imc::Announce::kSystemUuv);
  CHECK(announce.services == "imc+udp://127.0.0.1:6002/");
  CHECK(announce.lat_rad == Approx(59.9 * kRadPerDeg));

  const auto& sd = std::get<imc::SonarData>(got[2].message);
  CHECK(got[2].header.src_ent == imc::kImcEntitySonar);
  CHECK(got[2].header.timestamp_s == Approx(1767225600.0));
  CHECK(sd.type == imc::SonarData::kSidescan);
  CHECK(sd.frequency_hz == 600000);
  CHECK(sd.min_range_m == 0);
  CHECK(sd.max_range_m == 50);
  CHECK(sd.bits_per_point == 16);
  CHECK(sd.scale_factor == 1.0f);
  // port as stored (far to near), then starboard (near to far), little-endian
  CHECK(sd.data == std::vector<std::uint8_t>{0x02, 0x01, 0x04, 0x03, 0x06, 0x05, 0x0B, 0x0A, 0x0D,
                                             0x0C, 0x0F, 0x0E});

  const auto& es = std::get<imc::EstimatedState>(got[3].message);
  CHECK(got[3].header.src_ent == imc::kImcEntityNavigation);
  CHECK(got[3].header.timestamp_s == Approx(1767225600.1));
  CHECK(es.lat_rad == Approx(59.9 * kRadPerDeg));
  CHECK(es.lon_rad == Approx(10.75 * kRadPerDeg));
  CHECK(es.x_m == 12.0f);
  CHECK(es.y_m == -3.0f);
  CHECK(es.z_m == 14.0f);
  CHECK(es.depth_m == 14.0f);
  CHECK(es.alt_m == -1.0f);  // unknown
  CHECK(es.psi_rad == Approx(-0.5 * std::numbers::pi));
  CHECK(es.theta_rad == Approx(0.02));
  CHECK(es.phi_rad == Approx(-0.01));
  CHECK(es.u_m_s == Approx(2.0));
  CHECK(es.v_m_s == Approx(0.0).margin(1e-6));
  CHECK(es.vx_m_s == Approx(0.0).margin(1e-6));
  CHECK(es.vy_m_s == Approx(-2.0));
  CHECK(es.r_rad_s == Approx(0.05));

  RunStats stats;
  dev.add_stats(stats);
  CHECK(stats.imc_datagrams == 7);
  CHECK(stats.imc_dropped == 0);
  CHECK_THAT(dev.describe()[0], Catch::Contains("0x2050") && Catch::Contains("auv-test"));
}

TEST_CASE(
    "imc device: a run at --rate max, every ping and navigation sample over loopback, "
    "equal to the recording") {
  testing::TempDir dir("imc_run");
  net::UdpReceiver rx(net::HostPort{"127.0.0.1", 0});
  net::set_socket_buffer(rx.fd(), SO_RCVBUF, 8 << 20);
  // the receiver keeps reading while the run sends as fast as it renders
  std::vector<imc::Packet> got;
  std::atomic<bool> done{false};
  std::thread reader([&] {
    std::vector<std::uint8_t> buf(70000);
    while (true) {
      const auto d = rx.receive(buf, 100);
      if (!d) {
        if (done) break;
        continue;
      }
      imc::Packet p;
      if (imc::decode(std::span<const std::uint8_t>(buf.data(), d->datagram_size), p) ==
          imc::DecodeStatus::kOk)
        got.push_back(std::move(p));
    }
  });
  EmulatorOptions o;
  o.rate = parse_rate("max");
  o.threads = 2;
  o.duration_s = 2.0;
  o.record_dir = dir.file("rec");
  o.stats_interval_s = 0;
  o.epoch_utc_ns = kEpochNs;
  ImcDeviceOptions io;
  io.destination = net::HostPort{"127.0.0.1", rx.bound_port()};
  o.imc = io;
  MonotonicClock clock;
  EmulatorHooks hooks;
  hooks.message = [](std::string_view) {};
  RunStats stats;
  {
    Emulator emu(config::parse_scenario(testing::small_scenario_yaml(), "test.yaml"), o, clock,
                 hooks);
    stats = emu.run();
  }
  done = true;
  reader.join();
  REQUIRE(stats.imc_dropped == 0);
  CHECK(got.size() == stats.imc_datagrams);

  // the recording's pings, in order
  std::vector<xtf::XtfPing> recorded;
  xtf::XtfReader reader_xtf(dir.file("rec/pings.xtf"));
  xtf::XtfRecord packet;
  while (reader_xtf.next(packet))
    if (packet.is_ping) recorded.push_back(packet.ping);
  REQUIRE(recorded.size() == stats.pings_sent);

  std::size_t pings = 0, states = 0, heartbeats = 0, announces = 0;
  double last_state_t = 0.0;
  for (const imc::Packet& p : got) {
    if (const auto* sd = std::get_if<imc::SonarData>(&p.message)) {
      REQUIRE(pings < recorded.size());
      imc::SonarData expected;
      sonar_data_from_xtf(recorded[pings], ImcSonarInfo{0, 0}, expected);
      CHECK(sd->data == expected.data);
      CHECK(sd->max_range_m == 20);
      ++pings;
    } else if (std::holds_alternative<imc::EstimatedState>(p.message)) {
      CHECK(p.header.timestamp_s > last_state_t);  // in time order
      last_state_t = p.header.timestamp_s;
      ++states;
    } else if (std::holds_alternative<imc::Heartbeat>(p.message)) {
      ++heartbeats;
    } else if (std::holds_alternative<imc::Announce>(p.message)) {
      ++announces;
    }
  }
  CHECK(pings == stats.pings_sent);
  // one per position sample, 100 ms apart over the 2 s run (the 250 ms samples carry none)
  CHECK(states >= 20);
  CHECK(states <= 21);
  CHECK(states < stats.nav_samples);
  CHECK(heartbeats >= 2);
  CHECK(announces == 1);
}

TEST_CASE("imc device: float samples go as 16-bit units with a scale factor") {
  xtf::XtfPing ping;
  ping.channels.resize(2);
  ping.channels[0].samples = std::vector<float>{0.5f, 2.0f, 0.0f};
  ping.channels[1].samples = std::vector<float>{4.0f, 1.0f, 0.25f};
  imc::SonarData sd;
  sonar_data_from_xtf(ping, ImcSonarInfo{600e3, 50.0}, sd);
  CHECK(sd.bits_per_point == 16);
  CHECK(sd.scale_factor == Approx(4.0 / 65535.0));
  REQUIRE(sd.data.size() == 12);
  const std::vector<float> expected = {0.5f, 2.0f, 0.0f, 4.0f, 1.0f, 0.25f};
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const unsigned unit = sd.data[2 * k] | (static_cast<unsigned>(sd.data[2 * k + 1]) << 8);
    CHECK(unit * sd.scale_factor == Approx(expected[k]).margin(sd.scale_factor));
  }
}

TEST_CASE("pose input imc:udp: an EstimatedState moves the pose; other messages are ignored") {
  using namespace pose_test;
  const LocalTangentPlane ltp(kOrigin);
  InjectedClock clock;
  clock.value = 5'000'000'000;
  const auto source = open_pose_source("imc:udp:127.0.0.1:0", ltp, clock.fn());
  auto* udp = dynamic_cast<UdpPoseSource*>(source.get());
  REQUIRE(udp);
  CHECK_THAT(source->describe(), Catch::Contains("imc pose"));
  net::UdpSender tx(net::HostPort{"127.0.0.1", udp->bound_port()});
  std::vector<std::uint8_t> bytes;
  imc::Header h;
  h.src = 0x2051;
  imc::encode(h, imc::Heartbeat{}, bytes);
  REQUIRE(tx.send(bytes));
  // the reference point 100 m north of the origin, the vehicle 10 m south and 5 m west of it
  const GeoPoint ref = ltp.to_geodetic(100.0, 0.0);
  imc::EstimatedState e;
  e.lat_rad = ref.latitude_deg * kRadPerDeg;
  e.lon_rad = ref.longitude_deg * kRadPerDeg;
  e.x_m = -10.0f;
  e.y_m = -5.0f;
  e.depth_m = 12.5f;
  e.alt_m = 6.0f;
  e.psi_rad = -0.5f;
  e.theta_rad = 0.1f;
  e.phi_rad = -0.05f;
  imc::encode(h, e, bytes);
  REQUIRE(tx.send(bytes));
  REQUIRE(wait_until([&] { return source->latest().has_value(); }));
  const ExternalPose p = *source->latest();
  CHECK(p.has_position);
  CHECK(p.pose.position_W.x() == Approx(90.0).margin(0.01));
  CHECK(p.pose.position_W.y() == Approx(-5.0).margin(0.01));
  CHECK(p.has_depth);
  CHECK(p.pose.position_W.z() == Approx(12.5));
  CHECK(p.altitude_m == Approx(6.0));
  CHECK(p.pose.yaw == Approx(2.0 * std::numbers::pi - 0.5));
  CHECK(p.pose.pitch == Approx(0.1));
  CHECK(p.pose.roll == Approx(-0.05));
  CHECK(p.received_ns == 5'000'000'000);
  const PoseSourceStats s = source->stats();
  CHECK(s.updates == 1);
  CHECK(s.ignored == 1);
  CHECK(s.malformed == 0);
  CHECK(s.lost == 0);

  // a packet with a wrong CRC is malformed
  bytes.back() ^= 0xFF;
  REQUIRE(tx.send(bytes));
  REQUIRE(wait_until([&] { return source->stats().malformed == 1; }));
  CHECK_THAT(source->stats().last_error, Catch::Contains("CRC"));
}

TEST_CASE(
    "pose input imc: EstimatedState as a pose snapshot (invalid depth and altitude, "
    "non-finite fields)") {
  imc::EstimatedState e;
  e.lat_rad = 0.5;
  e.lon_rad = 0.1;
  e.depth_m = -1.0f;
  e.alt_m = -1.0f;
  std::string error;
  auto m = pose_message_from_imc(e, 1767225600.5, error);
  REQUIRE(m);
  CHECK(std::isnan(m->depth_m));
  CHECK(std::isnan(m->altitude_m));
  CHECK(m->latitude_deg == Approx(0.5 * kDegPerRad));
  CHECK(m->time_unix_ns == 1'767'225'600'500'000'000);
  CHECK(pose_message_from_imc(e, 0.0, error)->time_unix_ns == 0);  // no time stamp
  e.psi_rad = std::numeric_limits<float>::infinity();
  CHECK_FALSE(pose_message_from_imc(e, 1.0, error));
  CHECK_THAT(error, Catch::Contains("not finite"));
  e.psi_rad = 0.0f;
  e.lat_rad = 2.0;  // beyond the pole
  CHECK_FALSE(pose_message_from_imc(e, 1.0, error));
}
