// The socketcand server (drivers/can/socketcand_server.h): the protocol byte for byte, our client
// and python-can as readers and senders, port and client limits, IPv6. Its faults (slow, idle,
// garbage-sending and vanishing clients, 50 at once) are in socketcand_server_faults_test.cpp.
#include "drivers/can/socketcand_server.h"

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "drivers/can/socketcand_client.h"
#include "tests/drivers/can/socketcand_test_support.h"
#include "tests/support/skip.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop::can;
using namespace sonarloop::can::socketcand_test;
using sonarloop::net::HostPort;

TEST_CASE("socketcand server: byte-exact handshake and frames for a bare TCP client") {
  SocketcandServer server(kLoopbackAnyPort);
  REQUIRE(server.bound_port() != 0);
  CHECK(server.describe() == "socketcand server on 127.0.0.1:" +
                                 std::to_string(server.bound_port()) + " (channel vcan0)");
  RawClient c(server.bound_port());
  REQUIRE(c.get() == "< hi >");  // alone, as python-can's recv(256) demands
  c.put("< echo >");
  CHECK(c.get() == "< echo >");
  c.put("< rawmode >");  // before open: refused
  CHECK(c.get().starts_with("< error"));
  c.put("< open vcan0 >");
  REQUIRE(c.get() == "< ok >");
  c.put("< rawmode >");
  REQUIRE(c.get() == "< ok >");
  REQUIRE(wait_until([&] { return server.streaming_clients() == 1; }));
  CanFrame f = pattern(8).frame;
  server.send(f, 1699999999123456000);
  CHECK(c.get() == "\n< frame 09F80108 1699999999.123456 38393A3B3C3D3E3F >");
  // python-can 4.1 style send with two elements in one segment
  c.put("< send 9F80123 2 0 e6 >< send 123 1 ff >");
  const auto r1 = server.receive(5000);
  const auto r2 = server.receive(5000);
  REQUIRE(r1);
  REQUIRE(r2);
  CHECK(r1->id == 0x09F80123);
  CHECK(r1->extended);
  CHECK(r1->len == 2);
  CHECK(r1->data[1] == 0xE6);
  CHECK(r2->id == 0x123);
  CHECK_FALSE(r2->extended);
  CHECK_FALSE(server.receive(0));
  const auto s = server.stats();
  CHECK(s.frames_sent == 1);
  CHECK(s.frames_received == 2);
  CHECK(s.clients_accepted == 1);
  CHECK(s.protocol_errors == 1);
}

TEST_CASE("socketcand server: our client receives every frame in order and sends back") {
  SocketcandServer server(kLoopbackAnyPort);
  SocketcandClient client(HostPort{"127.0.0.1", server.bound_port()});
  SocketcandClient second(HostPort{"localhost", server.bound_port()});
  CHECK(client.connected());
  REQUIRE(wait_until([&] { return server.streaming_clients() == 2; }));

  constexpr int kFrames = 20000;
  std::atomic<int> ok_first{0};
  std::atomic<int> ok_second{0};
  auto reader = [](SocketcandClient& c, std::atomic<int>& ok) {
    for (int i = 0; i < kFrames; ++i) {
      const auto got = c.receive_timed(10000);
      if (!got) return;
      const TimedCanFrame want = pattern(i);
      if (!(got->frame == want.frame) || got->t_ns != want.t_ns) return;
      ok = i + 1;
    }
  };
  std::thread t1(reader, std::ref(client), std::ref(ok_first));
  std::thread t2(reader, std::ref(second), std::ref(ok_second));
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < kFrames; ++i) {
    const TimedCanFrame f = pattern(i);
    server.send(f.frame, f.t_ns);
  }
  const double send_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t1.join();
  t2.join();
  const double total_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(ok_first == kFrames);
  CHECK(ok_second == kFrames);
  std::printf(
      "socketcand server -> 2 clients: %d frames, send() %.2f us/frame, delivered to both "
      "at %.0f frames/s\n",
      kFrames, send_s / kFrames * 1e6, kFrames / total_s);

  // client -> server
  for (int i = 0; i < 1000; ++i) {
    client.send(pattern(i).frame, 0);
  }
  for (int i = 0; i < 1000; ++i) {
    const auto got = server.receive(10000);
    REQUIRE(got);
    REQUIRE(*got == pattern(i).frame);
  }
  const auto s = server.stats();
  CHECK(s.frames_sent == kFrames);
  CHECK(s.frames_received == 1000);
  CHECK(s.clients_dropped_slow == 0);
  CHECK(client.errors_received() == 0);
}

TEST_CASE("socketcand server: python-can's socketcand interface reads and writes live") {
  SocketcandServerOptions options;
  options.client_backlog_bytes = 4 << 20;  // python-can 4.1 reads 1 KiB per recv(); be patient
  SocketcandServer server(kLoopbackAnyPort, options);
  constexpr int kFrames = 5000;
  constexpr int kBack = 200;
  const std::string cmd = std::string(SONARLOOP_PYTHON) + " " + SONARLOOP_SOURCE_DIR +
                          "/tests/drivers/can/python_socketcand_peer.py 127.0.0.1 " +
                          std::to_string(server.bound_port()) + " " + std::to_string(kFrames) +
                          " " + std::to_string(kBack);
  std::atomic<int> rc{-2};
  std::thread python([&] { rc = sonarloop::testing::run_command(cmd); });
  const bool ready = wait_until([&] { return server.streaming_clients() == 1 || rc != -2; });
  if (!ready || server.streaming_clients() != 1) {
    python.join();
    FAIL("python-can did not connect (exit code " << rc << ")");
  }
  for (int i = 0; i < kFrames; ++i) {
    const TimedCanFrame f = pattern(i);
    server.send(f.frame, f.t_ns);
  }
  std::vector<CanFrame> back;
  while (back.size() < kBack) {
    const auto f = server.receive(30000);
    if (!f) break;
    back.push_back(*f);
  }
  python.join();
  CHECK(rc == 0);
  REQUIRE(back.size() == kBack);
  for (int j = 0; j < kBack; ++j) {
    CHECK(back[static_cast<std::size_t>(j)].id == 0x0DF11900u + static_cast<std::uint32_t>(j));
    CHECK(back[static_cast<std::size_t>(j)].extended);
    CHECK(back[static_cast<std::size_t>(j)].len == 4);
    CHECK(back[static_cast<std::size_t>(j)].data[0] == j);
    CHECK(back[static_cast<std::size_t>(j)].data[1] == 0xFF - j);
  }
  CHECK(server.stats().clients_dropped_slow == 0);
}

TEST_CASE("socketcand server: port in use, too many clients, shutdown") {
  SocketcandServerOptions one;
  one.max_clients = 1;
  one.on_warning = [](const std::string&) {};
  SocketcandServer server(kLoopbackAnyPort, one);
  const HostPort taken{"127.0.0.1", server.bound_port()};
  CHECK_THROWS_AS(SocketcandServer(taken), std::runtime_error);
  CHECK_THROWS_WITH(SocketcandServer(taken),
                    Catch::Contains("cannot listen on 127.0.0.1:" + std::to_string(taken.port)) &&
                        Catch::Contains("in use"));

  SocketcandClient first(taken);
  CHECK_THROWS_WITH(SocketcandClient(taken), Catch::Contains("too many clients"));
  CHECK(server.stats().clients_rejected == 1);

  // nobody listens: a clear connect error
  HostPort closed;
  {
    SocketcandServer tmp(kLoopbackAnyPort);
    closed = tmp.bound_address();
  }
  CHECK_THROWS_WITH(SocketcandClient(closed), Catch::Contains("cannot connect"));

  // stop(): the client sees the connection close, receive() on the server returns nothing
  server.stop();
  CHECK_THROWS_WITH(first.receive(5000), Catch::Contains("closed"));
  CHECK_FALSE(first.connected());
  CHECK_FALSE(server.receive(-1).has_value());
}

TEST_CASE("socketcand server: IPv6 loopback ::1", "[may_skip]") {
  std::unique_ptr<SocketcandServer> server;
  try {
    server = std::make_unique<SocketcandServer>(HostPort{"::1", 0});
  } catch (const std::runtime_error& e) {
    sonarloop::testing::skip_test(std::string("IPv6 loopback unavailable here: ") + e.what());
  }
  CHECK_THAT(server->describe(), Catch::Contains("[::1]:"));
  SocketcandClient client(HostPort{"::1", server->bound_port()});
  REQUIRE(wait_until([&] { return server->streaming_clients() == 1; }));
  server->send(pattern(5).frame, pattern(5).t_ns);
  const auto got = client.receive_timed(5000);
  REQUIRE(got);
  CHECK(got->frame == pattern(5).frame);
  CHECK(got->t_ns == pattern(5).t_ns);
}
