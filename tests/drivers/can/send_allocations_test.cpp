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
#include "tests/support/allocation_counter.h"
#include "tests/support/temp_dir.h"

using sonarloop::testing::allocations_in;

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
