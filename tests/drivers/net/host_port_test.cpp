#include "drivers/net/host_port.h"

#include <catch2/catch.hpp>
#include <stdexcept>

using namespace sonarloop::net;

TEST_CASE("net: parse_host_port accepts IPv4, bracketed IPv6 and localhost") {
  CHECK(parse_host_port("127.0.0.1:5600") == HostPort{"127.0.0.1", 5600});
  CHECK(parse_host_port("[::1]:29536") == HostPort{"::1", 29536});
  CHECK(parse_host_port("localhost:0") == HostPort{"localhost", 0});
  CHECK(parse_host_port("0.0.0.0:65535") == HostPort{"0.0.0.0", 65535});
  CHECK(to_string(HostPort{"::1", 5}) == "[::1]:5");
  CHECK(to_string(HostPort{"127.0.0.1", 5600}) == "127.0.0.1:5600");
  const SocketAddress a = resolve(HostPort{"localhost", 7});
  CHECK(a.family() == AF_INET);
  CHECK(to_host_port(a) == HostPort{"127.0.0.1", 7});
  CHECK(resolve(HostPort{"::1", 7}).family() == AF_INET6);
}

TEST_CASE("net: parse_host_port errors name the text and the problem") {
  using Catch::Contains;
  CHECK_THROWS_AS(parse_host_port("127.0.0.1"), std::invalid_argument);
  CHECK_THROWS_WITH(parse_host_port("127.0.0.1"), Contains("'127.0.0.1'") && Contains("PORT"));
  CHECK_THROWS_WITH(parse_host_port("127.0.0.1:"), Contains("missing port"));
  CHECK_THROWS_WITH(parse_host_port(":5600"), Contains("missing host"));
  CHECK_THROWS_WITH(parse_host_port("127.0.0.1:70000"), Contains("out of range 0..65535"));
  CHECK_THROWS_WITH(parse_host_port("127.0.0.1:56x"), Contains("not a number"));
  CHECK_THROWS_WITH(parse_host_port("127.0.0.1:-1"), Contains("not a number"));
  CHECK_THROWS_WITH(parse_host_port("::1:5600"), Contains("brackets"));
  CHECK_THROWS_WITH(parse_host_port("[::1:5600"), Contains("']'"));
  CHECK_THROWS_WITH(parse_host_port("example.com:5600"), Contains("numeric"));
  CHECK_THROWS_WITH(parse_host_port("300.1.1.1:5600"), Contains("'300.1.1.1'"));
}
