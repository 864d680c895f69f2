// The live view as one of the emulator's devices (web/emulator_device.h): the run's statistics
// as the page shows them, and every ping's datagram handed to the hub (real XTF pings, read back
// as line events by a subscribed client).
#include "web/emulator_device.h"

#include <catch2/catch.hpp>
#include <chrono>
#include <string>
#include <vector>

#include "drivers/xtf/xtf_file.h"

using namespace sonarloop;
using namespace std::chrono_literals;

namespace {

const std::string kIver2Xtf =
    std::string(SONARLOOP_SOURCE_DIR) + "/tests/data/xtf/scotsman-iver2.xtf";

bool is_event(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}

}  // namespace

TEST_CASE("the emulator's statistics as the page shows them") {
  emulator::RunStats s;
  s.sim_time_s = 12.5;
  s.pings_sent = 100;
  s.pings_late = 3;
  s.pings_dropped = 2;
  s.udp_dropped = 4;
  s.wall_time_s = 10.0;
  s.cpu_time_s = 5.0;
  const web::WebStats w = web::web_stats_of(s);
  CHECK(std::string(w.source) == "run");
  CHECK(w.sim_time_s == 12.5);
  CHECK(w.pings == 100);
  CHECK(w.deadline_misses == 5);
  CHECK(w.datagrams_lost == 4);
  CHECK(w.cpu_percent == Approx(50.0));
}

TEST_CASE("the device hands every datagram and the statistics to the hub") {
  web::WebHub hub;
  const auto client = hub.subscribe();
  REQUIRE(client);
  web::WebViewDevice device(hub);
  CHECK(device.on_wire());
  CHECK(device.describe().empty());

  xtf::XtfReader reader(kIver2Xtf);
  const emulator::PingSlot slot;
  device.ping(slot, reader.file_header_bytes());
  xtf::XtfRawPacket packet;
  int pushed = 0;
  while (pushed < 5 && reader.next_raw(packet)) {
    device.ping(slot, packet.bytes);
    ++pushed;
  }
  REQUIRE(pushed == 5);
  emulator::RunStats s;
  s.pings_sent = 77;
  device.stats(s);
  hub.close();  // the worker ends after the datagrams queued: every line and the statistics out

  int lines = 0, stats = 0;
  web::Event e;
  while (client->next(e, 1000ms) == web::WebClient::Next::kEvent) {
    if (is_event(*e, "event: line\n")) ++lines;
    if (is_event(*e, "event: stats\n")) {
      ++stats;
      CHECK(e->find("\"source\":\"run\"") != std::string::npos);
      CHECK(e->find("\"pings\":77") != std::string::npos);
    }
  }
  CHECK(lines > 0);
  CHECK(static_cast<std::uint64_t>(lines) == hub.counters().lines);
  CHECK(hub.counters().pings_not_shown == 0);
  CHECK(stats == 1);
}
