// Live SocketCAN I/O on vcan0. Needs a kernel with CAN support and a vcan0 interface that is up
// (`ip link add dev vcan0 type vcan && ip link set up vcan0`); otherwise the test prints why and
// exits 77, which ctest reports as skipped.
#include "drivers/can/socketcan.h"
#include "tests/support/skip.h"

#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>

#include <net/if.h>

using namespace sonarloop::can;

namespace {

[[noreturn]] void skip(const std::string& why) {
  sonarloop::testing::skip_test(why);
}

}  // namespace

TEST_CASE("socketcan: frames sent on vcan0 are received by a second socket") {
  std::string reason;
  if (!SocketCanTransport::kernel_supports_can(&reason))
    skip("socket(AF_CAN) fails on this kernel: " + reason);
  if (::if_nametoindex("vcan0") == 0) skip("no vcan0 interface");

  SocketCanTransport tx("vcan0");
  SocketCanTransport rx("vcan0");
  CHECK(tx.describe() == "socketcan vcan0");
  // drain anything already on the bus
  while (rx.receive(0)) {
  }
  for (std::uint32_t i = 0; i < 100; ++i) {
    CanFrame f;
    f.id = 0x09F80100u + i;
    f.extended = i % 5 != 0;
    if (!f.extended) f.id &= kCanSffMask;
    f.len = static_cast<std::uint8_t>(i % 9);
    for (std::uint8_t k = 0; k < f.len; ++k)
      f.data[k] = static_cast<std::uint8_t>(i + k);
    tx.send(f, 0);
    const auto got = rx.receive(2000);
    REQUIRE(got);
    CHECK(*got == f);
  }
  CHECK(tx.frames_sent() + tx.frames_dropped() == 100);
}
