#include "drivers/net/udp_receiver.h"
#include "drivers/net/udp_sender.h"

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include <sys/socket.h>

#include "tests/support/skip.h"
#include "tests/support/test_rng.h"

using namespace sonarloop::net;

namespace {

// Deterministic payload: a 4-byte sequence number then a pattern that depends on it.
void fill(std::vector<std::uint8_t>& buf, std::uint32_t seq) {
  for (std::size_t i = 0; i < buf.size(); ++i)
    buf[i] = static_cast<std::uint8_t>((i * 131u + seq * 7u) & 0xFF);
  for (std::size_t i = 0; i < 4 && i < buf.size(); ++i)
    buf[i] = static_cast<std::uint8_t>(seq >> (8 * i));
}

// Datagrams the receive buffer holds with margin (a 64 KiB datagram costs up to ~2x in skb
// overhead on loopback), so a send window of that many never overflows it.
std::size_t window_for(const UdpReceiver& rx, std::size_t max_size) {
  const std::size_t per = 4 * (max_size + 1024);
  return std::max<std::size_t>(1, static_cast<std::size_t>(rx.receive_buffer_bytes()) / per);
}

}  // namespace

TEST_CASE("udp: 1000 datagrams of varying sizes up to 65507 bytes arrive intact over 127.0.0.1") {
  UdpReceiver rx(HostPort{"127.0.0.1", 0}, 4 << 20);
  REQUIRE(rx.bound_port() != 0);
  UdpSender tx(HostPort{"127.0.0.1", rx.bound_port()}, 1 << 20);
  CHECK(tx.send_buffer_bytes() > 0);
  CHECK(rx.describe() == "udp on 127.0.0.1:" + std::to_string(rx.bound_port()));

  constexpr int kCount = 1000;
  sonarloop::testing::TestRng rng(0x4E7);
  std::vector<std::size_t> sizes(kCount);
  for (auto& s : sizes)
    s = 4 + static_cast<std::size_t>(rng.below(kMaxUdpDatagramBytes - 4 + 1));
  sizes[0] = kMaxUdpDatagramBytes;
  sizes[1] = 4;
  sizes[2] = kMaxUdpDatagramBytes;

  const std::size_t window = window_for(rx, kMaxUdpDatagramBytes);
  std::vector<std::uint8_t> out(kMaxUdpDatagramBytes);
  std::vector<std::uint8_t> expected;
  std::vector<std::uint8_t> in(kMaxUdpDatagramBytes + 1);
  std::size_t received = 0;
  std::size_t bytes = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t first = 0; first < kCount; first += window) {
    const std::size_t last = std::min<std::size_t>(kCount, first + window);
    for (std::size_t i = first; i < last; ++i) {
      out.resize(sizes[i]);
      fill(out, static_cast<std::uint32_t>(i));
      REQUIRE(tx.send(out));
    }
    for (std::size_t i = first; i < last; ++i) {
      const auto d = rx.receive(in, 5000);
      REQUIRE(d.has_value());
      REQUIRE_FALSE(d->truncated);
      REQUIRE(d->size == sizes[i]);
      expected.resize(sizes[i]);
      fill(expected, static_cast<std::uint32_t>(i));
      REQUIRE(std::equal(expected.begin(), expected.end(), in.begin()));
      ++received;
      bytes += d->size;
    }
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(received == kCount);
  CHECK(tx.datagrams_sent() == kCount);
  CHECK(tx.dropped() == 0);
  std::printf(
      "udp loopback: %d datagrams, %.1f MB in %.3f s = %.0f MB/s, %.0f datagrams/s "
      "(window %zu, SO_RCVBUF %d, SO_SNDBUF %d)\n",
      kCount, static_cast<double>(bytes) / 1e6, secs, static_cast<double>(bytes) / 1e6 / secs,
      kCount / secs, window, rx.receive_buffer_bytes(), tx.send_buffer_bytes());
  // nothing left over
  CHECK_FALSE(rx.receive(in, 0).has_value());
}

TEST_CASE("udp: oversize datagrams are rejected, truncation is flagged, timeouts return nothing") {
  UdpReceiver rx(HostPort{"127.0.0.1", 0});
  UdpSender tx(HostPort{"localhost", rx.bound_port()});
  std::vector<std::uint8_t> big(kMaxUdpDatagramBytes + 1, 0xAB);
  CHECK_THROWS_AS(tx.send(big), std::invalid_argument);
  CHECK_THROWS_WITH(tx.send(big), Catch::Contains("65508 bytes") && Catch::Contains("65507"));
  CHECK(tx.datagrams_sent() == 0);

  std::vector<std::uint8_t> small(100, 0x5A);
  REQUIRE(tx.send(small));
  std::vector<std::uint8_t> in(10);
  const auto d = rx.receive(in, 5000);
  REQUIRE(d);
  CHECK(d->truncated);
  CHECK(d->size == 10);
  CHECK(d->datagram_size == 100);
  CHECK(in[9] == 0x5A);

  // zero-length datagram
  REQUIRE(tx.send(std::span<const std::uint8_t>{}));
  const auto z = rx.receive(in, 5000);
  REQUIRE(z);
  CHECK(z->size == 0);
  CHECK_FALSE(z->truncated);

  CHECK_FALSE(rx.receive(in, 0).has_value());
  CHECK_FALSE(rx.receive(in, 20).has_value());
}

TEST_CASE("udp: a port in use gives a clear error naming the address") {
  UdpReceiver first(HostPort{"127.0.0.1", 0});
  const HostPort taken{"127.0.0.1", first.bound_port()};
  CHECK_THROWS_AS(UdpReceiver(taken), std::runtime_error);
  CHECK_THROWS_WITH(UdpReceiver(taken),
                    Catch::Contains(to_string(taken)) && Catch::Contains("in use"));
}

TEST_CASE("udp: a stream to a port nobody listens on is counted, never thrown") {
  HostPort closed;
  {
    UdpReceiver tmp(HostPort{"127.0.0.1", 0});
    closed = tmp.bound_address();
  }  // port released: nobody listens there now
  UdpSender tx(closed);
  std::vector<std::uint8_t> d(64, 1);
  for (int i = 0; i < 10; ++i)
    CHECK_NOTHROW(tx.send(d));
  CHECK(tx.datagrams_sent() + tx.dropped() == 10);
}

TEST_CASE("udp: IPv6 loopback ::1", "[may_skip]") {
  std::unique_ptr<UdpReceiver> rx;
  try {
    rx = std::make_unique<UdpReceiver>(HostPort{"::1", 0});
  } catch (const std::runtime_error& e) {
    sonarloop::testing::skip_test(std::string("IPv6 loopback unavailable here: ") + e.what());
  }
  UdpSender tx(HostPort{"::1", rx->bound_port()});
  std::vector<std::uint8_t> out(kMaxUdpDatagramBytes, 0x3C);
  REQUIRE(tx.send(out));
  std::vector<std::uint8_t> in(kMaxUdpDatagramBytes);
  const auto d = rx->receive(in, 5000);
  REQUIRE(d);
  CHECK(d->size == kMaxUdpDatagramBytes);
  CHECK(in == out);
}
