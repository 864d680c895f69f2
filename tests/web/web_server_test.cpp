// The live view's HTTP server (web/web_server.h) over real loopback connections: it serves the
// page, the statistics and the event stream and nothing else; a browser that stops reading never
// blocks the producer; and nothing a client does holds it: a request sent a byte at a time is cut
// off after the request timeout (408), an endless request line or header block is refused (431)
// and the connection closed after a bounded number of bytes, pipelined requests are answered in
// order, a flood of connections is answered in turn, the connection cap makes room for a new
// client, and stop() returns whatever the clients do (issue 29).
#include "web/web_server.h"

#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <future>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "web/web_hub.h"
#include "web/web_page.h"

using namespace sonarloop;
using namespace std::chrono_literals;

namespace {

// Waits (polling) until `done()` or about 10 s: for work on other threads, never a timing check.
template <class F>
bool eventually(F done) {
  for (int i = 0; i < 1000; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(10ms);
  }
  return done();
}

bool begins_with(const std::string& s, const std::string& prefix) {
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

// Everything until the peer closes (or 10 s of silence).
std::string read_all(int fd) {
  return read_until(fd, "\x01never\x01");
}

// Whether the peer has something to read (or has closed) within `ms`.
bool readable(int fd, int ms) {
  pollfd p{fd, POLLIN, 0};
  return ::poll(&p, 1, ms) == 1;
}

// Sends `chunk` over and over until the server answers or closes, up to `max_bytes`; the bytes
// that went.
std::size_t send_until_answered(int fd, const std::string& chunk, std::size_t max_bytes) {
  std::size_t sent = 0;
  while (sent < max_bytes) {
    pollfd p{fd, POLLIN | POLLOUT, 0};
    if (::poll(&p, 1, 10000) != 1 || (p.revents & (POLLIN | POLLERR | POLLHUP))) break;
    const ssize_t n = ::send(fd, chunk.data(), chunk.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n < 0 && errno != EAGAIN) break;
    if (n > 0) sent += static_cast<std::size_t>(n);
  }
  return sent;
}

std::size_t count_of(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1))
    ++n;
  return n;
}

}  // namespace

TEST_CASE("a browser that stops reading never blocks the producer and gets the newest") {
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
  CHECK(begins_with(got, "HTTP/1.1 200 OK\r\n"));
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

TEST_CASE("the server serves the page, the statistics and nothing else") {
  web::WebHub hub;
  web::WebServer server(hub, {"localhost", 0});
  CHECK(server.address().host == "127.0.0.1");
  const std::uint16_t port = server.address().port;
  CHECK(server.url() == "http://127.0.0.1:" + std::to_string(port) + "/");

  const std::string page = http(port, "GET", "/");
  CHECK(begins_with(page, "HTTP/1.1 200 OK\r\n"));
  CHECK(page.find("Content-Type: text/html; charset=utf-8") != std::string::npos);
  CHECK(page.find("<canvas id=\"waterfall\"") != std::string::npos);
  // self-contained: nothing loaded from elsewhere
  CHECK(page.find("src=\"http") == std::string::npos);
  CHECK(page.find("href=\"http") == std::string::npos);

  const std::string stats = http(port, "GET", "/stats.json");
  CHECK(begins_with(stats, "HTTP/1.1 200 OK\r\n"));
  CHECK(stats.find("\"events_dropped\":0") != std::string::npos);

  CHECK(begins_with(http(port, "GET", "/etc/passwd"), "HTTP/1.1 404 "));
  CHECK(begins_with(http(port, "GET", "/../index.html"), "HTTP/1.1 4"));
  const std::string post = http(port, "POST", "/");
  CHECK(begins_with(post, "HTTP/1.1 405 "));
  CHECK(post.find("\r\nAllow: GET, HEAD\r\n") != std::string::npos);
  CHECK(begins_with(http(port, "DELETE", "/events"), "HTTP/1.1 405 "));
  // HEAD: the page's headers, its length, no body
  const std::string head = http(port, "HEAD", "/");
  CHECK(begins_with(head, "HTTP/1.1 200 OK\r\n"));
  CHECK(head.find("Content-Length: " + std::to_string(std::string_view(web::kWebPage).size())) !=
        std::string::npos);
  CHECK(head.size() == head.find("\r\n\r\n") + 4);

  // a second server on the same port is refused with the address
  try {
    web::WebServer twice(hub, {"127.0.0.1", port});
    FAIL("bound twice");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find("127.0.0.1:" + std::to_string(port)) != std::string::npos);
  }
}

TEST_CASE("a request sent a byte at a time is cut off after the request timeout, with 408") {
  web::WebHub hub;
  web::WebServerOptions o;
  o.request_timeout = 300ms;
  web::WebServer server(hub, {"127.0.0.1", 0}, o);
  const int fd = connect_loopback(server.address().port, 0);
  send_all(fd, "GET / HTTP/1.1\r\n");
  // a header byte every 50 ms, each well within any per-byte timeout, for up to 10 s: the
  // server must answer (408) and close long before the request could ever be whole
  int bytes = 0;
  while (bytes < 200 && !readable(fd, 50)) {
    if (::send(fd, "X", 1, MSG_NOSIGNAL) != 1) break;
    ++bytes;
  }
  CHECK(bytes < 200);
  CHECK(begins_with(read_all(fd), "HTTP/1.1 408 Request Timeout\r\n"));
  ::close(fd);
  CHECK(eventually([&] { return server.counters().timeouts == 1; }));
  CHECK(server.counters().requests == 0);
}

TEST_CASE("an endless request line or header block is refused with 431, and no more is read") {
  web::WebHub hub;
  web::WebServerOptions o;
  o.max_head_bytes = 1024;
  web::WebServer server(hub, {"127.0.0.1", 0}, o);
  struct Case {
    std::string start, repeat;
  };
  const std::vector<Case> cases = {{"GET /", std::string(4096, 'a')},
                                   {"GET / HTTP/1.1\r\nHost: a\r\n", "X-a: b\r\n"},
                                   {"GET / HTTP/1.1\r\nHost: a\r\n", std::string(4096, 'b')}};
  for (const Case& c : cases) {
    INFO(c.start + c.repeat.substr(0, 8));
    const int fd = connect_loopback(server.address().port, 0);
    send_all(fd, c.start);
    // 256 MB offered: the server answers after its 1 KiB limit and closes; what it took
    // is the limit, what it drops while it closes (256 KiB) and the sockets' buffers
    constexpr std::size_t kOffered = std::size_t{256} << 20;
    const std::size_t sent = send_until_answered(fd, c.repeat, kOffered);
    CHECK(sent < kOffered / 8);
    CHECK(begins_with(read_all(fd), "HTTP/1.1 431 Request Header Fields Too Large\r\n"));
    ::close(fd);
  }
  // too many fields, each short: 431 too
  const int fd = connect_loopback(server.address().port, 0);
  std::string many = "GET / HTTP/1.1\r\nHost: a\r\n";
  for (int i = 0; i < net::kMaxHttpHeaderFields; ++i)
    many += "X: y\r\n";
  web::WebServerOptions big;
  web::WebServer roomy(hub, {"127.0.0.1", 0}, big);
  const int fd2 = connect_loopback(roomy.address().port, 0);
  send_all(fd2, many + "\r\n");
  CHECK(begins_with(read_all(fd2), "HTTP/1.1 431 "));
  ::close(fd2);
  ::close(fd);
  CHECK(server.counters().bad_requests == 3);
  CHECK(roomy.counters().bad_requests == 1);
}

TEST_CASE("pipelined requests are answered in order on one connection") {
  web::WebHub hub;
  web::WebServer server(hub, {"127.0.0.1", 0});
  const int fd = connect_loopback(server.address().port, 0);
  send_all(fd,
           "GET /stats.json HTTP/1.1\r\nHost: a\r\n\r\n"
           "GET /nothing HTTP/1.1\r\nHost: a\r\n\r\n"
           "HEAD / HTTP/1.1\r\nHost: a\r\n\r\n"
           "GET / HTTP/1.1\r\nHost: a\r\nConnection: close\r\n\r\n");
  const std::string got = read_all(fd);  // ends when the server closes after the last
  ::close(fd);
  const std::size_t a = got.find("HTTP/1.1 200 OK\r\nContent-Type: application/json");
  const std::size_t b = got.find("HTTP/1.1 404 ");
  const std::size_t c = got.find("HTTP/1.1 200 OK\r\nContent-Type: text/html", b);
  const std::size_t d = got.find("HTTP/1.1 200 OK\r\nContent-Type: text/html", c + 1);
  CHECK(a == 0);
  CHECK(b != std::string::npos);
  CHECK(c != std::string::npos);
  REQUIRE(d != std::string::npos);
  CHECK((a < b && b < c && c < d));
  CHECK(count_of(got, "HTTP/1.1 ") == 4);
  CHECK(count_of(got, "<canvas id=\"waterfall\"") == 1);  // HEAD has no body
  CHECK(got.find("Connection: close") > c);
  CHECK(server.counters().requests == 4);
}

TEST_CASE("a flood of connections is answered in turn, beyond the connection cap") {
  web::WebHub hub;
  web::WebServerOptions o;
  o.max_connections = 8;
  web::WebServer server(hub, {"127.0.0.1", 0}, o);
  // 200 connections at once, each with its request: those beyond the cap wait in the accept
  // queue (a short backlog would have the kernel drop and retry their handshakes)
  constexpr int kClients = 200;
  std::vector<int> fds;
  for (int i = 0; i < kClients; ++i) {
    fds.push_back(connect_loopback(server.address().port, 0));
    send_all(fds.back(), "GET /stats.json HTTP/1.1\r\nHost: a\r\nConnection: close\r\n\r\n");
  }
  int answered = 0;
  for (int fd : fds) {
    if (begins_with(read_all(fd), "HTTP/1.1 200 OK\r\n")) ++answered;
    ::close(fd);
  }
  CHECK(answered == kClients);
  CHECK(server.counters().connections == kClients);
  CHECK(server.counters().evicted == 0);
}

TEST_CASE("at the connection cap, a new client takes an idle connection's place") {
  web::WebHub hub;
  web::WebServerOptions o;
  o.max_connections = 4;
  web::WebServer server(hub, {"127.0.0.1", 0}, o);
  // four connections that never send a request
  std::vector<int> idle;
  for (int i = 0; i < 4; ++i)
    idle.push_back(connect_loopback(server.address().port, 0));
  REQUIRE(eventually([&] { return server.counters().connections == 4; }));
  // a browser still gets its page: the longest-waiting idle connection makes room
  CHECK(begins_with(http(server.address().port, "GET", "/stats.json"), "HTTP/1.1 200 OK\r\n"));
  CHECK(server.counters().evicted == 1);
  CHECK(readable(idle[0], 5000));  // the first one was closed
  for (int fd : idle)
    ::close(fd);

  // four event streams fill the cap and are never replaced: a fifth connection waits in the
  // accept queue until one of them leaves
  std::vector<int> streams;
  for (int i = 0; i < 4; ++i) {
    streams.push_back(connect_loopback(server.address().port, 0));
    send_all(streams.back(), "GET /events HTTP/1.1\r\nHost: a\r\n\r\n");
  }
  REQUIRE(eventually([&] { return hub.counters().clients == 4; }));
  const int late = connect_loopback(server.address().port, 0);
  send_all(late, "GET /stats.json HTTP/1.1\r\nHost: a\r\nConnection: close\r\n\r\n");
  CHECK(!readable(late, 1500));
  ::close(streams[0]);
  CHECK(begins_with(read_all(late), "HTTP/1.1 200 OK\r\n"));
  ::close(late);
  for (std::size_t i = 1; i < streams.size(); ++i)
    ::close(streams[i]);
}

TEST_CASE("stop() returns whatever the clients do, and ends every stream") {
  web::WebHubOptions ho;
  ho.client_queue_events = 1000;
  web::WebHub hub(ho);
  auto server = std::make_unique<web::WebServer>(hub, net::HostPort{"127.0.0.1", 0});
  const std::uint16_t port = server->address().port;
  // a stream that reads nothing with megabytes queued, a request half sent, an idle connection
  const int stalled = connect_loopback(port, 4096);
  send_all(stalled, "GET /events HTTP/1.1\r\nHost: a\r\n\r\n");
  const int reader = connect_loopback(port, 0);
  send_all(reader, "GET /events HTTP/1.1\r\nHost: a\r\n\r\n");
  REQUIRE(eventually([&] { return hub.counters().clients == 2; }));
  const std::string pad(4000, 'x');
  for (int i = 0; i < 1000; ++i)
    hub.broadcast("test", "{\"pad\":\"" + pad + "\"}");
  const int half = connect_loopback(port, 0);
  send_all(half, "GET / HTTP/1.1\r\nHo");
  const int idle = connect_loopback(port, 0);
  // stop() must return (a hang fails here after 30 s; how long it took is not the test's)
  auto stopped = std::async(std::launch::async, [&] { server->stop(); });
  REQUIRE(stopped.wait_for(30s) == std::future_status::ready);
  // every connection is closed: the stream that reads sees its end after what was sent
  CHECK(read_all(reader).find("event: test") != std::string::npos);
  CHECK(read_all(half).empty());
  CHECK(read_all(idle).empty());
  for (int fd : {stalled, reader, half, idle})
    ::close(fd);
  CHECK(hub.counters().clients == 0);
  server.reset();
}
