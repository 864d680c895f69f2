// The live web view's hub (web/web_hub.h): bounded per-client queues that drop their oldest
// events and count them; a catch-up for a new client; real XTF pings turned into line events.
// Its HTTP server has tests/web/web_server_test.cpp.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "drivers/xtf/xtf_file.h"
#include "web/web_events.h"
#include "web/web_hub.h"

using namespace sonarloop;
using namespace std::chrono_literals;

namespace {

const std::string kXtf = std::string(SONARLOOP_SOURCE_DIR) + "/tests/data/xtf/scotsman-iver2.xtf";

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}

// Every event a client has queued, until it stays quiet for 1 s.
std::vector<std::string> drain(web::WebClient& client) {
  std::vector<std::string> out;
  web::Event e;
  while (client.next(e, 1000ms) == web::WebClient::Next::kEvent)
    out.push_back(*e);
  return out;
}

}  // namespace

TEST_CASE("a client's queue drops its oldest events when full and counts them") {
  web::WebClient client(4);
  for (int i = 0; i < 10; ++i) {
    std::string e = "e";  // (not "e" + ...: a GCC 12 false -Wrestrict)
    e += std::to_string(i);
    client.push(std::make_shared<const std::string>(e));
  }
  const std::vector<std::string> got = drain(client);
  CHECK(got == std::vector<std::string>{"e6", "e7", "e8", "e9"});
  CHECK(client.dropped() == 6);
  CHECK(client.delivered() == 4);
}

TEST_CASE("the hub refuses clients beyond max_clients and gives a new client the catch-up") {
  web::WebHubOptions o;
  o.max_clients = 2;
  web::WebHub hub(o);
  atr::Contact c;
  c.id = 7;
  c.class_name = "manta";
  c.mine_like = true;
  c.north_m = 12.5;
  hub.push_contact(c);
  web::WebStats s;
  s.pings = 42;
  hub.push_stats(s);

  const auto a = hub.subscribe();
  const auto b = hub.subscribe();
  REQUIRE(a);
  REQUIRE(b);
  CHECK_FALSE(hub.subscribe());
  CHECK(hub.counters().clients_refused == 1);
  CHECK(hub.counters().clients == 2);

  // a's catch-up: the contact and the stats; then the stats the worker publishes
  const std::vector<std::string> got = drain(*a);
  REQUIRE(got.size() >= 2);
  CHECK(starts_with(got[0], "event: contact\ndata: {\"contact\":7,"));
  CHECK(got[0].find("\"class\":\"manta\"") != std::string::npos);
  CHECK(starts_with(got[1], "event: stats\ndata: {\"source\":\"run\""));
  CHECK(got[1].find("\"pings\":42") != std::string::npos);

  hub.unsubscribe(a);
  CHECK(hub.counters().clients == 1);
  CHECK(hub.subscribe());
}

TEST_CASE("real XTF pings become line events of 512 pixels per side with the track") {
  web::WebHub hub;
  const auto client = hub.subscribe();
  REQUIRE(client);
  xtf::XtfReader reader(kXtf);
  REQUIRE(hub.push_datagram(reader.file_header_bytes(), true));
  xtf::XtfRawPacket packet;
  int pushed = 0;
  while (pushed < 60 && reader.next_raw(packet))
    pushed += hub.push_datagram(packet.bytes, true) ? 1 : 0;
  REQUIRE(pushed == 60);

  int lines = 0;
  for (const std::string& e : drain(*client)) {
    if (!starts_with(e, "event: line\n")) continue;
    ++lines;
    // base64 of 512 bytes: 684 characters
    const auto p = e.find("\"port\":\"");
    const auto s = e.find("\"stbd\":\"");
    REQUIRE(p != std::string::npos);
    REQUIRE(s != std::string::npos);
    CHECK(e.find('"', p + 8) - (p + 8) == 684);
    CHECK(e.find('"', s + 8) - (s + 8) == 684);
    CHECK(e.find("\"north_m\":") != std::string::npos);
  }
  // every sonar ping of the file's first packets, in order (none dropped: the pushes waited)
  CHECK(lines > 0);
  CHECK(static_cast<std::uint64_t>(lines) == hub.counters().lines);
  CHECK(hub.counters().pings_not_shown == 0);
  // a late client gets the track
  const auto late = hub.subscribe();
  REQUIRE(late);
  web::Event first;
  REQUIRE(late->next(first, 1000ms) == web::WebClient::Next::kEvent);
  CHECK(starts_with(*first, "event: track\ndata: {\"north_m\":["));
}

TEST_CASE("levels are coded over the display span, and base64 is RFC 4648") {
  CHECK(web::level_byte(-200.0f) == 0);
  CHECK(web::level_byte(web::kDisplayMinDb) == 0);
  CHECK(web::level_byte(web::kDisplayMaxDb) == 255);
  CHECK(web::level_byte(-30.0f) == 128);  // 127.5 rounds up
  const std::vector<float> flat(2048, -30.0f);
  std::vector<std::uint8_t> px(512);
  web::reduce_line(flat, px);
  for (auto b : px)
    CHECK(b == 128);
  const std::string text = "foobar";
  const auto bytes = [&](std::size_t n) {
    return std::span(reinterpret_cast<const std::uint8_t*>(text.data()), n);
  };
  CHECK(web::base64(bytes(0)) == "");
  CHECK(web::base64(bytes(1)) == "Zg==");
  CHECK(web::base64(bytes(2)) == "Zm8=");
  CHECK(web::base64(bytes(3)) == "Zm9v");
  CHECK(web::base64(bytes(6)) == "Zm9vYmFy");
}
