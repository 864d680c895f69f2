#include "drivers/can/can_transport.h"

#include <catch2/catch.hpp>
#include <chrono>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "drivers/can/socketcan.h"
#include "drivers/can/socketcand_client.h"
#include "drivers/can/socketcand_server.h"
#include "tests/drivers/can/nav_frame.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop::can;
using sonarloop::testing::nav_frame;

TEST_CASE("can transport factory: none and log:FILE") {
  auto none = open_can_transport("none");
  CHECK(none->describe() == "none");
  none->send(nav_frame(), 0);
  CHECK_FALSE(none->can_receive());
  CHECK_THROWS_AS(none->receive(0), std::logic_error);

  sonarloop::testing::TempDir dir("can-factory");
  const std::string path = dir.file("nav.log");
  {
    auto log = open_can_transport("log:" + path, CanTransportOptions{"can1"});
    CHECK(log->describe() == "candump log " + path);
    log->send(nav_frame(), 1699999999123456000);
    log->flush();
    CHECK_THROWS_WITH(log->receive(0), Catch::Contains("cannot receive"));
  }
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  CHECK(ss.str() == "(1699999999.123456) can1 09F80123#00E6B523B1AC6A06\n");
  CHECK_THROWS_WITH(open_can_transport("log:"), Catch::Contains("missing file name"));
}

TEST_CASE("can transport factory: socketcand:HOST:PORT serves frames") {
  auto t = open_can_transport("socketcand:127.0.0.1:0");
  auto* server = dynamic_cast<SocketcandServer*>(t.get());
  REQUIRE(server != nullptr);
  CHECK(t->can_receive());
  SocketcandClient client(sonarloop::net::HostPort{"127.0.0.1", server->bound_port()});
  for (int i = 0; i < 6000 && server->streaming_clients() == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  t->send(nav_frame(), 1);
  const auto got = client.receive(5000);
  REQUIRE(got);
  CHECK(*got == nav_frame());
  CHECK_THROWS_WITH(open_can_transport("socketcand:127.0.0.1"), Catch::Contains("PORT"));
  CHECK_THROWS_WITH(open_can_transport("socketcand:127.0.0.1:99999"),
                    Catch::Contains("out of range"));
}

TEST_CASE("can transport factory: bad specs and SocketCAN errors are clear") {
  CHECK_THROWS_WITH(open_can_transport("udp://x"),
                    Catch::Contains("not a CAN transport") && Catch::Contains("socketcand:"));
  CHECK_THROWS_AS(open_can_transport(""), std::invalid_argument);
  CHECK_THROWS_AS(open_can_transport("averyveryverylongname0"), std::invalid_argument);

  std::string reason;
  if (!SocketCanTransport::kernel_supports_can(&reason)) {
    // the message the user sees on a kernel without CAN (like the project's machines)
    CHECK_THROWS_WITH(open_can_transport("vcan0"),
                      "SocketCAN is not available on this kernel (socket(AF_CAN): " + reason +
                          "); use --can socketcand:HOST:PORT or --can log:FILE");
    CHECK(reason == "Address family not supported by protocol");
  } else {
    // a kernel with CAN: an interface that does not exist is named
    CHECK_THROWS_WITH(open_can_transport("nosuchcan7"), Catch::Contains("'nosuchcan7' not found"));
  }
}
