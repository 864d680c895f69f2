// The socketcand server against the faults of the outside world (issue 11 section 4): a client
// that stops reading, idle and half-open connections, 50 clients at once, clients beyond the
// slots, clients that never read, send garbage or disconnect mid-frame. The publisher must never
// block and every well-behaved reader must get every frame in order.
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

TEST_CASE("socketcand server: a client that stops reading is dropped, send() never blocks") {
  std::vector<std::string> warnings;
  std::mutex warnings_mu;
  SocketcandServerOptions options;
  options.client_backlog_bytes = 16 * 1024;
  options.rawmode_start_delay_ms = 0;
  options.on_warning = [&](const std::string& w) {
    std::lock_guard lock(warnings_mu);
    warnings.push_back(w);
  };
  SocketcandServer server(kLoopbackAnyPort, options);
  RawClient slow(server.bound_port(), 4096);
  slow.handshake();
  REQUIRE(wait_until([&] { return server.streaming_clients() == 1; }));
  // the kernel buffers a few MB on loopback; the bound keeps a broken server from looping forever
  long sent = 0;
  while (server.stats().clients_dropped_slow == 0 && sent < 5'000'000) {
    server.send(pattern(static_cast<int>(sent % 1000)).frame, sent);
    ++sent;
  }
  std::printf("slow client dropped after %ld frames\n", sent);
  CHECK(server.stats().clients_dropped_slow == 1);
  REQUIRE(wait_until([&] { return server.connected_clients() == 0; }));
  // every frame is either received whole by the client (what the kernel had taken before the
  // drop still arrives, then the close) or counted as dropped: a frame cut off counts as dropped
  const std::string stream = slow.read_to_eof();
  long whole = 0;
  for (std::size_t at = stream.find("\n< frame "); at != std::string::npos;
       at = stream.find("\n< frame ", at + 1)) {
    const std::size_t end = stream.find('>', at);
    if (end != std::string::npos && stream.find('\n', at + 1) > end) ++whole;
  }
  std::printf("received whole %ld, dropped %llu\n", whole,
              static_cast<unsigned long long>(server.stats().frames_dropped_slow));
  CHECK(whole > 0);
  CHECK(server.stats().frames_dropped_slow > 0);
  CHECK(whole + static_cast<long>(server.stats().frames_dropped_slow) == sent);
  {
    std::lock_guard lock(warnings_mu);
    REQUIRE(warnings.size() == 1);
    CHECK_THAT(warnings[0], Catch::Contains("dropped client 127.0.0.1:") &&
                                Catch::Contains("too slow") &&
                                Catch::Contains(std::to_string(server.stats().frames_dropped_slow) +
                                                " frames it did not receive"));
  }
  // the server goes on serving new clients
  SocketcandClient fresh(HostPort{"127.0.0.1", server.bound_port()});
  REQUIRE(wait_until([&] { return server.streaming_clients() == 1; }));
  server.send(pattern(3).frame, 42'000);
  const auto got = fresh.receive_timed(5000);
  REQUIRE(got);
  CHECK(got->frame == pattern(3).frame);
  CHECK(got->t_ns == 42'000);
}

TEST_CASE("socketcand server: idle connections that never open the bus do not lock clients out") {
  std::vector<std::string> warnings;
  std::mutex warnings_mu;
  SocketcandServerOptions options;  // 16 clients, as in `run --can socketcand:...`
  options.on_warning = [&](const std::string& w) {
    std::lock_guard lock(warnings_mu);
    warnings.push_back(w);
  };
  SocketcandServer server(kLoopbackAnyPort, options);
  REQUIRE(options.max_clients == 16);
  std::vector<std::unique_ptr<RawClient>> idle;
  for (std::size_t i = 0; i < options.max_clients; ++i) {
    idle.push_back(std::make_unique<RawClient>(server.bound_port()));
    REQUIRE(idle.back()->get() == "< hi >");  // and then nothing, ever
  }
  REQUIRE(wait_until([&] { return server.connected_clients() == 16; }));
  // a real client still gets in: the oldest idle connection makes room
  SocketcandClient client(HostPort{"127.0.0.1", server.bound_port()});
  REQUIRE(wait_until([&] { return server.streaming_clients() == 1; }));
  CHECK(idle.front()->closed_within(5000));
  server.send(pattern(4).frame, pattern(4).t_ns);
  const auto got = client.receive_timed(5000);
  REQUIRE(got);
  CHECK(got->frame == pattern(4).frame);
  const auto s = server.stats();
  CHECK(s.clients_rejected == 0);
  CHECK(s.clients_dropped_handshake == 1);
  // the server thread counts the eviction, then warns: wait for the warning
  REQUIRE(wait_until([&] {
    std::lock_guard lock(warnings_mu);
    return !warnings.empty();
  }));
  std::lock_guard lock(warnings_mu);
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::Contains("evicted") && Catch::Contains("< open CHANNEL >"));
}

TEST_CASE("socketcand server: a client that never sends open is closed after the timeout") {
  std::vector<std::string> warnings;
  std::mutex warnings_mu;
  SocketcandServerOptions options;
  options.handshake_timeout_ms = 200;
  options.rawmode_start_delay_ms = 0;
  options.on_warning = [&](const std::string& w) {
    std::lock_guard lock(warnings_mu);
    warnings.push_back(w);
  };
  SocketcandServer server(kLoopbackAnyPort, options);
  RawClient opened(server.bound_port());
  opened.handshake();
  RawClient idle(server.bound_port());
  REQUIRE(idle.get() == "< hi >");
  CHECK(idle.closed_within(20000));
  REQUIRE(wait_until([&] { return server.stats().clients_dropped_handshake == 1; }));
  // the client that opened the bus in time keeps streaming
  CHECK(server.streaming_clients() == 1);
  server.send(pattern(2).frame, 2'000);
  CHECK(opened.get() == "\n< frame 09F80102 0.000002 0E0F >");
  // the server thread counts the drop, then warns: wait for the warning
  REQUIRE(wait_until([&] {
    std::lock_guard lock(warnings_mu);
    return !warnings.empty();
  }));
  std::lock_guard lock(warnings_mu);
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::Contains("no '< open CHANNEL >' within 200 ms"));
}

TEST_CASE("socketcand server: 50 clients at once each receive every frame in order") {
  constexpr int kClients = 50;
  constexpr int kFrames = 2000;
  SocketcandServerOptions options;
  options.max_clients = kClients;
  SocketcandServer server(kLoopbackAnyPort, options);
  // every client connects, handshakes and reads on its own thread, all at the same time
  std::vector<int> ok(kClients, -1);
  std::vector<std::thread> threads;
  for (int k = 0; k < kClients; ++k) {
    threads.emplace_back([&, k] {
      try {
        SocketcandClient client(HostPort{"127.0.0.1", server.bound_port()});
        ok[static_cast<std::size_t>(k)] = read_pattern(client, kFrames);
      } catch (const std::exception& e) {
        std::printf("client %d: %s\n", k, e.what());
      }
    });
  }
  const bool all_streaming = wait_until([&] { return server.streaming_clients() == kClients; });
  if (all_streaming) send_pattern(server, 0, kFrames);
  for (auto& t : threads)
    t.join();
  REQUIRE(all_streaming);
  CHECK(std::count(ok.begin(), ok.end(), kFrames) == kClients);
  const auto s = server.stats();
  CHECK(s.frames_sent == kFrames);
  CHECK(s.clients_accepted == kClients);
  CHECK(s.clients_rejected == 0);
  CHECK(s.clients_dropped_slow == 0);
  CHECK(s.clients_dropped_handshake == 0);
  CHECK(s.protocol_errors == 0);
}

TEST_CASE("socketcand server: with the default 16 slots, 34 more clients are refused and counted") {
  WarningLog log;
  SocketcandServerOptions options;
  options.on_warning = log.sink();
  SocketcandServer server(kLoopbackAnyPort, options);
  REQUIRE(options.max_clients == 16);
  const HostPort address{"127.0.0.1", server.bound_port()};
  std::vector<std::unique_ptr<SocketcandClient>> admitted;
  for (int k = 0; k < 16; ++k)
    admitted.push_back(std::make_unique<SocketcandClient>(address));
  REQUIRE(wait_until([&] { return server.streaming_clients() == 16; }));
  // a refused client reads "< error too many clients >" and then the close, never a hang
  int refused = 0;
  for (int k = 16; k < 50; ++k) {
    try {
      SocketcandClient extra(address);
    } catch (const std::runtime_error& e) {
      if (std::string(e.what()).find("too many clients") != std::string::npos) ++refused;
    }
  }
  CHECK(refused == 34);
  // the 16 go on receiving
  send_pattern(server, 0, 100);
  int complete = 0;
  for (auto& c : admitted)
    complete += read_pattern(*c, 100) == 100 ? 1 : 0;
  CHECK(complete == 16);
  const auto s = server.stats();
  CHECK(s.clients_accepted == 16);
  CHECK(s.clients_rejected == 34);
  CHECK(server.connected_clients() == 16);
  REQUIRE(wait_until([&] { return log.count_containing("rejected client") == 34; }));
  CHECK(log.count_containing("already 16 clients with the bus open") == 34);
}

TEST_CASE(
    "socketcand server: clients that never read are dropped, counted, the publisher runs on") {
  // 4 clients open the bus and then never read; one reads everything. Proof that send() never
  // blocks, by counting: each silent client is dropped only once its socket buffers and its
  // bounded backlog are full, so a blocking send() would have stopped there; every call after
  // those drops returns too, and the reader misses nothing.
  constexpr int kSilent = 4;
  constexpr int kBatches = 100;
  constexpr int kBatch = 1000;
  constexpr int kFrames = kBatches * kBatch;
  WarningLog log;
  SocketcandServerOptions options;
  options.client_backlog_bytes = 16 * 1024;
  options.rawmode_start_delay_ms = 0;
  options.on_warning = log.sink();
  SocketcandServer server(kLoopbackAnyPort, options);
  std::vector<std::unique_ptr<RawClient>> silent;
  for (int k = 0; k < kSilent; ++k) {
    silent.push_back(std::make_unique<RawClient>(server.bound_port(), 4096));
    silent.back()->handshake();
  }
  SocketcandClient reader(HostPort{"127.0.0.1", server.bound_port()});
  REQUIRE(wait_until([&] { return server.streaming_clients() == kSilent + 1; }));
  std::atomic<int> read_ok{0};
  std::thread reading([&] { read_pattern(reader, kFrames, &read_ok); });

  // the publisher: batches, each waiting for the reader (so that only the silent ones lag)
  int returned = 0;
  int returned_at_last_drop = -1;
  for (int b = 0; b < kBatches; ++b) {
    send_pattern(server, b * kBatch, (b + 1) * kBatch);
    returned += kBatch;
    if (returned_at_last_drop < 0 && server.stats().clients_dropped_slow == kSilent)
      returned_at_last_drop = returned;
    if (!wait_until([&] { return read_ok >= returned || !reader.connected(); })) break;
  }
  reading.join();
  std::printf("%d silent clients: all dropped after %d of %d frames; the reader got %d\n", kSilent,
              returned_at_last_drop, kFrames, read_ok.load());
  CHECK(returned == kFrames);
  CHECK(read_ok == kFrames);
  CHECK(returned_at_last_drop > 0);
  CHECK(returned_at_last_drop < kFrames);  // the publisher went on after the last drop
  const auto s = server.stats();
  CHECK(s.frames_sent == kFrames);
  CHECK(s.clients_dropped_slow == kSilent);
  CHECK(s.clients_disconnected == 0);
  REQUIRE(wait_until([&] { return server.connected_clients() == 1; }));
  CHECK(log.count_containing("too slow") == kSilent);
  for (auto& c : silent)
    CHECK(c->closed_within(5000));
}

TEST_CASE("socketcand server: clients that send garbage are refused or dropped, others unharmed") {
  WarningLog log;
  SocketcandServerOptions options;
  options.rawmode_start_delay_ms = 0;
  options.on_warning = log.sink();
  SocketcandServer server(kLoopbackAnyPort, options);
  SocketcandClient good(HostPort{"127.0.0.1", server.bound_port()});
  REQUIRE(wait_until([&] { return server.streaming_clients() == 1; }));
  const auto port = server.bound_port();

  // bytes outside any element: dropped at once, whatever follows
  RawClient binary(port);
  REQUIRE(binary.get() == "< hi >");
  std::string noise(64 * 1024, '\0');
  for (std::size_t i = 0; i < noise.size(); ++i)
    noise[i] = static_cast<char>((i * 131 + 7) & 0xFF);
  noise[0] = '\x01';
  binary.put(noise);
  CHECK(binary.closed_within(5000));

  // an element that never closes: dropped once it passes the element limit
  RawClient endless(port);
  REQUIRE(endless.get() == "< hi >");
  endless.put("< open " + std::string(4000, 'x'));
  CHECK(endless.closed_within(5000));

  // well-formed elements that mean nothing, before open: an error reply each, still connected
  RawClient confused(port);
  REQUIRE(confused.get() == "< hi >");
  confused.put("< >");
  CHECK(confused.get().starts_with("< error"));
  confused.put("< frobnicate 1 2 3 >");
  CHECK(confused.get().starts_with("< error"));
  confused.put("< open >");  // no channel
  CHECK(confused.get().starts_with("< error"));

  // in rawmode: malformed sends and unknown commands are counted and skipped, valid ones go on
  RawClient raw(port);
  raw.handshake();
  raw.put("< send XYZ 1 00 >< send 123 9 >< send 123 2 11 >< bogus >< send 123 1 5a >");
  const auto valid = server.receive(5000);
  REQUIRE(valid);
  CHECK(valid->id == 0x123);
  CHECK(valid->len == 1);
  CHECK(valid->data[0] == 0x5A);
  CHECK_FALSE(server.receive(0));

  // the reader saw nothing of it
  send_pattern(server, 0, 500);
  CHECK(read_pattern(good, 500) == 500);
  REQUIRE(wait_until([&] { return server.connected_clients() == 3; }));  // good, confused, raw
  const auto s = server.stats();
  CHECK(s.frames_received == 1);
  // 3 before open, 4 in rawmode, 2 stream errors (the noise, the endless element)
  CHECK(s.protocol_errors == 9);
  CHECK(s.clients_dropped_slow == 0);
  CHECK(log.count_containing("protocol error") == 2);
  CHECK(good.errors_received() == 0);
}

TEST_CASE(
    "socketcand server: clients that disconnect mid-frame are counted, nothing else changes") {
  WarningLog log;
  SocketcandServerOptions options;
  options.rawmode_start_delay_ms = 0;
  options.client_backlog_bytes = 8 << 20;
  options.on_warning = log.sink();
  SocketcandServer server(kLoopbackAnyPort, options);
  constexpr int kTotal = 150'000;
  SocketcandClient good(HostPort{"127.0.0.1", server.bound_port()});
  const auto port = server.bound_port();

  // half an element sent, then gone: during the handshake and in the middle of a "< send >"
  RawClient half_open(port);
  REQUIRE(half_open.get() == "< hi >");
  half_open.put("< op");
  half_open.close_now(false);
  RawClient half_send(port);
  half_send.handshake();
  half_send.put("< send 123 2 11 2");
  half_send.close_now(false);

  // a reset while the server still has frames for it: a non-reading client takes about 5 MB,
  // more than the kernel buffers for it on loopback (about 3.5 MB: the slow-client test above),
  // so the rest, a frame cut at whatever byte the kernel stopped, waits in its backlog (8 MiB, so
  // it is not dropped as slow); then it vanishes with a TCP RST
  RawClient vanishing(port, 4096);
  vanishing.handshake();
  REQUIRE(wait_until([&] { return server.streaming_clients() == 2; }));
  constexpr int kBeforeReset = 110'000;
  std::atomic<int> read_ok{0};
  std::thread reading([&] { read_pattern(good, kTotal, &read_ok); });
  // paced by the reader, so that only the silent client lags
  for (int sent = 0; sent < kBeforeReset; sent += 1000) {
    send_pattern(server, sent, sent + 1000);
    if (!wait_until([&] { return read_ok >= sent + 1000 || !good.connected(); })) break;
  }
  vanishing.close_now(true);
  // the publisher goes on; the server notices the reset on its next write or read
  send_pattern(server, kBeforeReset, kTotal);
  reading.join();
  CHECK(read_ok == kTotal);
  REQUIRE(wait_until([&] { return server.connected_clients() == 1; }));
  const auto s = server.stats();
  CHECK(s.clients_disconnected == 3);
  CHECK(s.clients_dropped_slow == 0);
  CHECK(s.frames_received == 0);  // the half "< send >" is never a frame
  CHECK(s.protocol_errors == 0);
  CHECK(s.frames_sent == kTotal);
  CHECK(server.streaming_clients() == 1);
}
