// The emulator's output devices (emulator/device.h) on their own: the sonar's UDP stream (the
// file header first and again after kHeaderRepeatS of simulation time, one datagram per ping,
// its counters) over a real socket on 127.0.0.1; the navigation bus on a candump log; the
// recorder's files and counters; the MCAP recording's contacts. Which device is on the wire
// decides what the publisher times.
#include <algorithm>
#include <catch2/catch.hpp>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "drivers/net/udp_receiver.h"
#include "emulator/emulator.h"
#include "emulator/mcap_device.h"
#include "emulator/nav_can_device.h"
#include "emulator/recorder_device.h"
#include "emulator/sonar_udp_device.h"
#include "emulator/xtf_ping.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;
using namespace sonarloop::emulator;

namespace {

PingSlot slot_at(SimTime t, std::int64_t k) {
  PingSlot s;
  s.index = k;
  s.truth.t = t;
  return s;
}

// the sizes of the datagrams waiting on `rx`
std::vector<std::size_t> drain(net::UdpReceiver& rx) {
  std::vector<std::size_t> sizes;
  std::vector<std::uint8_t> buf(70000);
  while (const auto d = rx.receive(buf, 200))
    sizes.push_back(d->datagram_size);
  return sizes;
}

}  // namespace

TEST_CASE("sonar UDP device: file header first and every 2 s of simulation time, then pings") {
  net::UdpReceiver rx(net::HostPort{"127.0.0.1", 0});
  const std::vector<std::uint8_t> header(1024, 0x7B);
  const std::vector<std::uint8_t> packet(300, 0x01);
  SonarUdpDevice udp(net::HostPort{"127.0.0.1", rx.bound_port()}, 0, header, packet.size());
  CHECK(udp.on_wire());
  const SimTime s = kNanosecondsPerSecond;
  udp.ping(slot_at(0, 0), packet);          // header, ping
  udp.ping(slot_at(s, 1), packet);          // ping
  udp.ping(slot_at(2 * s - 1, 2), packet);  // ping: not yet 2 s since the header
  udp.ping(slot_at(2 * s, 3), packet);      // header, ping
  CHECK(drain(rx) == std::vector<std::size_t>{1024, 300, 300, 300, 1024, 300});
  RunStats stats;
  udp.add_stats(stats);
  CHECK(stats.udp_datagrams == 6);
  CHECK(stats.udp_header_datagrams == 2);
  CHECK(stats.udp_bytes == 2 * 1024 + 4 * 300);
  CHECK(stats.udp_dropped == 0);
  REQUIRE(udp.describe().size() == 1);
  CHECK_THAT(udp.describe()[0], Catch::Contains("127.0.0.1") && Catch::Contains("300 bytes"));
}

TEST_CASE("navigation CAN device: every frame of a sample on its transport, flushed at close") {
  testing::TempDir dir("devices_can");
  const std::string log = dir.file("nav.log");
  NavCanDevice can(can::open_can_transport("log:" + log));
  CHECK(can.on_wire());
  std::vector<can::CanFrame> frames(3);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    frames[i].id = 0x09F80100u + static_cast<std::uint32_t>(i);
    frames[i].extended = true;
    frames[i].len = 8;
  }
  can.ping(slot_at(0, 0), {});  // a ping is not the bus's: nothing written
  can.nav(frames, 1'767'225'600'000'000'000);
  can.close();
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  std::size_t lines = 0;
  for (const char c : text.str())
    lines += c == '\n';
  CHECK(lines == 3);
  CHECK_THAT(text.str(), Catch::Contains("09F80100#") && Catch::Contains("09F80102#"));
  CHECK_THAT(can.describe()[0], Catch::Contains("NMEA 2000"));
}

TEST_CASE("recorder device: not on the wire; its files and counters") {
  testing::TempDir dir("devices_record");
  const render::SonarSetup setup =
      render::make_sonar_setup(render::SonarDesc{}, scene::WaterDesc{});
  const xtf::XtfFileHeader header = make_xtf_file_header(setup, "test", "");
  std::vector<std::string> warnings;
  RecorderDevice rec(std::make_unique<Recording>(dir.path().string(), header),
                     [&](const std::string& w) { warnings.push_back(w); });
  CHECK_FALSE(rec.on_wire());
  std::vector<can::CanFrame> frames(2);
  for (auto& f : frames) {
    f.id = 0x09F80100u;
    f.extended = true;
    f.len = 8;
  }
  rec.nav(frames, 1'767'225'600'000'000'000);
  rec.close();
  RunStats stats;
  rec.add_stats(stats);
  CHECK(stats.recorded_pings == 0);
  CHECK(stats.recording_error.empty());
  CHECK(warnings.empty());
  CHECK(std::filesystem::exists(dir.path() / "pings.xtf"));
  CHECK(std::filesystem::exists(dir.path() / "nav.log"));
  CHECK(std::filesystem::file_size(dir.path() / "nav.log") > 0);
  CHECK_THAT(rec.describe()[0], Catch::Contains("pings.xtf"));
}

TEST_CASE("MCAP device: contacts from any thread, written at close by time and id") {
  testing::TempDir dir("devices_mcap");
  mcap::WriterOptions plain;
  plain.compress = false;  // so that the messages' bytes can be found in the file
  McapDevice mcap(dir.file("r.mcap"), LocalTangentPlane(GeoPoint{55.9, -3.2}), McapSonarInfo{},
                  plain);
  CHECK_FALSE(mcap.on_wire());
  CHECK_THROWS_AS(mcap.add_contact({}), std::logic_error);  // not before record_contacts()
  mcap.record_contacts();
  // given out of order, two threads at once; one without a time (recorded at the last ping's,
  // here none: 0)
  std::thread a([&] {
    mcap.add_contact({3'000, 5, 1.0, 2.0, "{\"c\":\"t3-id5\"}"});
    mcap.add_contact({1'000, 9, 1.0, 2.0, "{\"c\":\"t1-id9\"}"});
  });
  std::thread b([&] {
    mcap.add_contact({3'000, 2, 1.0, 2.0, "{\"c\":\"t3-id2\"}"});
    mcap.add_contact({std::nullopt, 7, 1.0, 2.0, "{\"c\":\"none-id7\"}"});
  });
  a.join();
  b.join();
  mcap.close();
  mcap.close();  // again: nothing more
  RunStats stats;
  mcap.add_stats(stats);
  CHECK(stats.mcap_error.empty());
  CHECK(stats.mcap_messages == 8);  // a string and a fix each
  const std::string file = testing::slurp(dir.file("r.mcap"));
  CHECK_THAT(file, Catch::Contains("/contacts/fix") && Catch::Contains("std_msgs/msg/String"));
  std::vector<std::size_t> at;
  for (const char* c : {"none-id7", "t1-id9", "t3-id2", "t3-id5"}) {
    INFO(c);
    // once each, in the summary-free data section
    const std::size_t p = file.find(c);
    REQUIRE(p != std::string::npos);
    CHECK(file.find(c, p + 1) == std::string::npos);
    at.push_back(p);
  }
  CHECK(std::is_sorted(at.begin(), at.end()));
}
