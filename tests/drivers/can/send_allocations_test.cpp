// The per-frame send paths the emulator calls (NMEA 2000 encode, candump log, socketcand server,
// UDP) allocate nothing once set up: counted by replacing the global operator new for this test
// executable, on the calling thread only (the socketcand I/O thread may allocate).
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <new>
#include <thread>
#include <vector>

#include "drivers/can/candump_log.h"
#include "drivers/can/socketcand_client.h"
#include "drivers/can/socketcand_server.h"
#include "drivers/n2k/messages.h"
#include "drivers/net/udp_receiver.h"
#include "drivers/net/udp_sender.h"
#include "tests/support/temp_dir.h"

namespace {
thread_local bool g_counting = false;
thread_local long g_allocations = 0;
}  // namespace

// Every replaceable non-aligned form is replaced, so allocation and release always pair malloc
// with free (AddressSanitizer checks the pairing).
void* operator new(std::size_t size) {
  if (g_counting) ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  return operator new(size);
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  if (g_counting) ++g_allocations;
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept {
  return operator new(size, tag);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}

namespace {

// Allocations made by f() on this thread.
template <class F>
long allocations_in(F&& f) {
  g_allocations = 0;
  g_counting = true;
  f();
  g_counting = false;
  return g_allocations;
}

}  // namespace

using namespace sonarloop;

TEST_CASE("send paths: n2k encode, candump, socketcand and UDP sends do not allocate") {
  const n2k::Attitude att{7, 0.1, -0.2, 0.3};
  const n2k::PositionRapidUpdate pos{59.9, 10.7};
  can::CanFrame frame;
  CHECK(allocations_in([&] {
          for (int i = 0; i < 1000; ++i) {
            frame = n2k::encode(att, 0x23);
            frame = n2k::encode(pos, 0x23);
            const auto d = n2k::decode<n2k::Attitude>(frame);
            static_cast<void>(d);
          }
        }) == 0);

  testing::TempDir dir("send-alloc");
  can::CandumpLogWriter log(dir.file("a.log"));
  log.write(frame, 0);  // the stdio buffer is allocated by the first write
  CHECK(allocations_in([&] {
          for (int i = 0; i < 10000; ++i)
            log.write(frame, i * 1000);
        }) == 0);

  can::SocketcandServerOptions options;
  options.rawmode_start_delay_ms = 0;
  can::SocketcandServer server(net::HostPort{"127.0.0.1", 0}, options);
  can::SocketcandClient client(net::HostPort{"127.0.0.1", server.bound_port()});
  for (int i = 0; i < 6000 && server.streaming_clients() == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  REQUIRE(server.streaming_clients() == 1);
  CHECK(allocations_in([&] {
          for (int i = 0; i < 1000; ++i)
            server.send(frame, i);
        }) == 0);
  for (int i = 0; i < 1000; ++i)
    REQUIRE(client.receive(5000));

  net::UdpReceiver rx(net::HostPort{"127.0.0.1", 0});
  net::UdpSender tx(net::HostPort{"127.0.0.1", rx.bound_port()});
  std::vector<std::uint8_t> datagram(8000, 0x55);
  CHECK(allocations_in([&] {
          for (int i = 0; i < 10; ++i)
            tx.send(datagram);
        }) == 0);
}
