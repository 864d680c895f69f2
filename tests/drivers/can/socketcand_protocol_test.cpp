#include "drivers/can/socketcand_protocol.h"

#include <catch2/catch.hpp>
#include <string>

#include "tests/drivers/can/nav_frame.h"

using namespace sonarloop::can;
using sonarloop::testing::nav_frame;

TEST_CASE("socketcand: frame and send elements are formatted as docs/formats.md 4.4 shows") {
  char buf[128];
  const std::size_t n = format_socketcand_frame(nav_frame(), 1699999999123456789, buf, sizeof buf);
  CHECK(std::string(buf, n) == "\n< frame 09F80123 1699999999.123456 00E6B523B1AC6A06 >");

  CanFrame sff;
  sff.id = 0x7;
  sff.extended = false;
  sff.len = 0;
  format_socketcand_frame(sff, 5'000'000, buf, sizeof buf);
  CHECK(std::string(buf) == "\n< frame 007 0.005000  >");
  CHECK(format_socketcand_frame(sff, 0, buf, 20) == 0);

  format_socketcand_send(nav_frame(), buf, sizeof buf);
  CHECK(std::string(buf) == "< send 09F80123 8 00 E6 B5 23 B1 AC 6A 06 >");
  format_socketcand_send(sff, buf, sizeof buf);
  CHECK(std::string(buf) == "< send 007 0 >");
}

TEST_CASE("socketcand: parsing frame and send elements, python-can 4.1 style included") {
  std::string error;
  const auto f =
      parse_socketcand_frame("< frame 09F80123 1699999999.123456 00E6B523B1AC6A06 >", error);
  REQUIRE(f);
  CHECK(f->frame == nav_frame());
  CHECK(f->t_ns == 1699999999123456000);
  const auto empty = parse_socketcand_frame("< frame 123 1.5  >", error);
  REQUIRE(empty);
  CHECK_FALSE(empty->frame.extended);
  CHECK(empty->frame.len == 0);
  CHECK(empty->t_ns == 1'500'000'000);

  // python-can 4.1: unpadded id, lowercase unpadded bytes
  const auto s = parse_socketcand_send("< send 9F80123 8 0 e6 b5 23 b1 ac 6a 6 >", error);
  REQUIRE(s);
  CHECK(s->extended);
  CHECK(*s == nav_frame());
  // upstream: padded ids decide the frame type
  const auto sff = parse_socketcand_send("< send 123 2 11 22 >", error);
  REQUIRE(sff);
  CHECK_FALSE(sff->extended);
  CHECK(sff->len == 2);
  const auto eff_small = parse_socketcand_send("< send 00000123 0 >", error);
  REQUIRE(eff_small);
  CHECK(eff_small->extended);

  CHECK_FALSE(parse_socketcand_send("< send 123 3 11 22 >", error));
  CHECK_THAT(error, Catch::Contains("data byte 2"));
  CHECK_FALSE(parse_socketcand_send("< send 123 1 11 22 >", error));
  CHECK_THAT(error, Catch::Contains("more data bytes"));
  CHECK_FALSE(parse_socketcand_send("< send 123 9 >", error));
  CHECK_THAT(error, Catch::Contains("bad length"));
  CHECK_FALSE(parse_socketcand_send("< send XYZ 0 >", error));
  CHECK_THAT(error, Catch::Contains("bad CAN id"));
  CHECK_FALSE(parse_socketcand_send("< send 123 1 123 >", error));
  CHECK_FALSE(parse_socketcand_frame("< frame 123 x.5 00 >", error));
  CHECK_THAT(error, Catch::Contains("timestamp"));
  CHECK_FALSE(parse_socketcand_frame("< frame 123 1.5 0 >", error));
  CHECK_FALSE(parse_socketcand_frame("< ok >", error));
}

TEST_CASE("socketcand: the stream parser cuts coalesced and split elements") {
  SocketcandStreamParser p;
  std::string error;
  const std::string stream =
      "< hi >< ok >\n< frame 09F80123 1.000000 00 >\n  < frame 123 2.000000 0102 >";
  // feed one byte at a time: elements appear exactly when their '>' arrives
  std::vector<std::string> got;
  for (char c : stream) {
    p.append(&c, 1);
    while (auto e = p.next(error))
      got.push_back(*e);
    REQUIRE(error.empty());
  }
  REQUIRE(got.size() == 4);
  CHECK(got[0] == "< hi >");
  CHECK(got[1] == "< ok >");
  CHECK(got[2] == "< frame 09F80123 1.000000 00 >");
  CHECK(got[3] == "< frame 123 2.000000 0102 >");
  CHECK(p.buffered() == 0);

  SocketcandStreamParser bad;
  bad.append("junk", 4);
  CHECK_FALSE(bad.next(error));
  CHECK_THAT(error, Catch::Contains("outside"));

  SocketcandStreamParser endless;
  const std::string open(200, 'x');
  endless.append("<", 1);
  endless.append(open.data(), open.size());
  error.clear();
  CHECK_FALSE(endless.next(error));
  CHECK_THAT(error, Catch::Contains("no '>'"));

  const auto el = split_socketcand_element("<  open   vcan0 >");
  REQUIRE(el);
  CHECK(el->command == "open");
  CHECK(el->args == "vcan0");
}
