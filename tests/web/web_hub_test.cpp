// The live web view's hub and server (web/): bounded per-client queues that drop their
// oldest events and count them; a catch-up for a new client; real XTF pings turned into line
// events; and over a real loopback HTTP connection, a browser that stops reading never blocks
// the producer, loses its oldest events (counted) and still gets the newest; only the page, the
// events and the statistics are served.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "drivers/xtf/xtf_file.h"
#include "tests/support/skip.h"
#include "web/web_events.h"
#include "web/web_hub.h"
#include "web/web_server.h"

using namespace sonarloop;
using namespace std::chrono_literals;

namespace {

const std::string kXtf = std::string(SONARLOOP_SOURCE_DIR) + "/tests/data/xtf/scotsman-iver2.xtf";

// Waits (polling) until `done()` or about 10 s: for work on other threads, never a timing check.
template <class F>
bool eventually(F done) {
  for (int i = 0; i < 1000; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(10ms);
  }
  return done();
}

// Every event a client has queued, until it stays quiet for 1 s.
std::vector<std::string> drain(web::WebClient& client) {
  std::vector<std::string> out;
  web::Event e;
  while (client.next(e, 1000ms) == web::WebClient::Next::kEvent)
    out.push_back(*e);
  return out;
}

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}

// A TCP connection to 127.0.0.1:port with a small receive buffer (a slow browser's).
int connect_loopback(std::uint16_t port, int receive_buffer_bytes) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  REQUIRE(fd >= 0);
  if (receive_buffer_bytes > 0) {
    ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &receive_buffer_bytes, sizeof receive_buffer_bytes);
  }
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  REQUIRE(::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0);
  timeval tv{10, 0};  // a server that never answers fails the test instead of hanging it
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  return fd;
}

void send_all(int fd, const std::string& s) {
  REQUIRE(::send(fd, s.data(), s.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(s.size()));
}

// Reads until `stop` appears in what was read, or the peer closes, or 10 s of silence.
std::string read_until(int fd, const std::string& stop) {
  std::string got;
  char buf[65536];
  while (got.find(stop) == std::string::npos) {
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    got.append(buf, static_cast<std::size_t>(n));
  }
  return got;
}

// One whole HTTP exchange on a fresh connection (Connection: close): the response.
std::string http(std::uint16_t port, const std::string& method, const std::string& path) {
  const int fd = connect_loopback(port, 0);
  send_all(fd, method + " " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n" +
                   (method == "POST" ? "Content-Length: 0\r\n" : "") + "\r\n");
  const std::string response = read_until(fd, "\x01never\x01");
  ::close(fd);
  return response;
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

TEST_CASE("over HTTP, a browser that stops reading never blocks the producer and gets the newest",
          "[may_skip]") {
  if (!web::web_available()) {
    sonarloop::testing::skip_test("built without cpp-httplib");
  }
  web::WebHubOptions o;
  o.client_queue_events = 64;
  web::WebHub hub(o);
  web::WebServer server(hub, {"127.0.0.1", 0});
  REQUIRE(server.address().port != 0);

  // a browser that opens the stream and then reads nothing
  const int fd = connect_loopback(server.address().port, 4096);
  send_all(fd, "GET /events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  REQUIRE(eventually([&] { return hub.counters().clients == 1; }));

  // 3000 events of 2 KB (6 MB): far more than the socket buffers and the queue hold; every
  // broadcast returns (a producer that waited for the reader would hang here)
  const std::string pad(2000, 'x');
  constexpr int kEvents = 3000;
  for (int i = 0; i < kEvents; ++i)
    hub.broadcast("test", "{\"n\":" + std::to_string(i) + ",\"pad\":\"" + pad + "\"}");
  CHECK(hub.counters().events == kEvents);
  REQUIRE(eventually([&] { return hub.counters().events_dropped > 0; }));

  // now read: the stream's events come in order, with a gap, and end with the newest
  const std::string got = read_until(fd, "{\"n\":" + std::to_string(kEvents - 1) + ",");
  ::close(fd);
  CHECK(starts_with(got, "HTTP/1.1 200 OK\r\n"));
  CHECK(got.find("Content-Type: text/event-stream") != std::string::npos);
  std::vector<int> seen;
  for (std::size_t at = got.find("{\"n\":"); at != std::string::npos;
       at = got.find("{\"n\":", at + 1))
    seen.push_back(std::atoi(got.c_str() + at + 5));
  REQUIRE(!seen.empty());
  CHECK(seen.back() == kEvents - 1);
  CHECK(static_cast<int>(seen.size()) < kEvents);
  for (std::size_t i = 1; i < seen.size(); ++i)
    CHECK(seen[i] > seen[i - 1]);
  // the drops are counted and reported in the statistics
  const web::WebHubCounters c = hub.counters();
  CHECK(c.events_dropped >= static_cast<std::uint64_t>(kEvents) - seen.size() - 64);
  CHECK(hub.stats_json().find("\"events_dropped\":" + std::to_string(c.events_dropped)) !=
        std::string::npos);
}

TEST_CASE("the server serves the page, the statistics and nothing else", "[may_skip]") {
  if (!web::web_available()) {
    sonarloop::testing::skip_test("built without cpp-httplib");
  }
  web::WebHub hub;
  web::WebServer server(hub, {"localhost", 0});
  CHECK(server.address().host == "127.0.0.1");
  const std::uint16_t port = server.address().port;
  CHECK(server.url() == "http://127.0.0.1:" + std::to_string(port) + "/");

  const std::string page = http(port, "GET", "/");
  CHECK(starts_with(page, "HTTP/1.1 200 OK\r\n"));
  CHECK(page.find("Content-Type: text/html; charset=utf-8") != std::string::npos);
  CHECK(page.find("<canvas id=\"waterfall\"") != std::string::npos);
  // self-contained: nothing loaded from elsewhere
  CHECK(page.find("src=\"http") == std::string::npos);
  CHECK(page.find("href=\"http") == std::string::npos);

  const std::string stats = http(port, "GET", "/stats.json");
  CHECK(starts_with(stats, "HTTP/1.1 200 OK\r\n"));
  CHECK(stats.find("\"events_dropped\":0") != std::string::npos);

  CHECK(starts_with(http(port, "GET", "/etc/passwd"), "HTTP/1.1 404 "));
  CHECK(starts_with(http(port, "GET", "/../index.html"), "HTTP/1.1 4"));
  CHECK(starts_with(http(port, "POST", "/"), "HTTP/1.1 404 "));
  CHECK(starts_with(http(port, "DELETE", "/events"), "HTTP/1.1 404 "));

  // a second server on the same port is refused with the address
  try {
    web::WebServer twice(hub, {"127.0.0.1", port});
    FAIL("bound twice");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find("127.0.0.1:" + std::to_string(port)) != std::string::npos);
  }
}
