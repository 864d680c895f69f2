// The pose message of `run --pose-from udp:...` (drivers/pose/pose_message.h, pose_message.md): the
// documented example byte for byte, and malformed datagrams refused with a reason.
#include "drivers/pose/pose_message.h"

#include <catch2/catch.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include <limits>

#include "tests/drivers/pose/sample_pose.h"

using namespace sonarloop;
using namespace sonarloop::pose;
using Catch::Matchers::Contains;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

PoseMessage message(std::uint32_t seq) {
  return testing::sample_pose_message(seq);
}

// The example datagram of drivers/pose/pose_message.md.
const std::vector<std::uint8_t> kExampleDatagram = {
    0x53, 0x4C, 0x50, 0x4D, 0x01, 0x00, 0x50, 0x00, 0x2A, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x15, 0xCD, 0x55, 0xF5, 0x51, 0x72, 0x86, 0x18, 0x23, 0x53, 0x99, 0xBD, 0xC7, 0xF4, 0x4D, 0x40,
    0x01, 0x9E, 0x59, 0xB7, 0xE6, 0x87, 0x25, 0x40, 0x00, 0x00, 0x00, 0x00, 0x00, 0xC0, 0x41, 0x40,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x28, 0x40, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xF8, 0x3F,
    0x7B, 0x14, 0xAE, 0x47, 0xE1, 0x7A, 0x94, 0xBF, 0x7B, 0x14, 0xAE, 0x47, 0xE1, 0x7A, 0x84, 0x3F};

}  // namespace

// ---------------------------------------------------------------------------------------------
// the pose message

TEST_CASE("pose message: the documented example encodes and decodes byte for byte") {
  PoseMessage m;
  m.sequence = 42;
  m.time_unix_ns = 1'767'225'600'123'456'789;  // 2026-01-01T00:00:00.123456789Z
  m.latitude_deg = 59.9123456;
  m.longitude_deg = 10.7654321;
  m.depth_m = 35.5;
  m.altitude_m = 12.25;
  m.heading_rad = 1.5;
  m.pitch_rad = -0.02;
  m.roll_rad = 0.01;
  const auto bytes = encode_pose_message(m);
  CHECK(std::vector<std::uint8_t>(bytes.begin(), bytes.end()) == kExampleDatagram);
  std::string error;
  const auto d = decode_pose_message(kExampleDatagram, error);
  REQUIRE(d);
  CHECK(d->sequence == 42);
  CHECK(d->time_unix_ns == m.time_unix_ns);
  CHECK(d->latitude_deg == m.latitude_deg);
  CHECK(d->longitude_deg == m.longitude_deg);
  CHECK(d->depth_m == 35.5);
  CHECK(d->altitude_m == 12.25);
  CHECK(d->heading_rad == 1.5);
  CHECK(d->pitch_rad == -0.02);
  CHECK(d->roll_rad == 0.01);
  // NaN = not available survives the round trip
  PoseMessage empty;
  const auto e = decode_pose_message(encode_pose_message(empty), error);
  REQUIRE(e);
  CHECK(std::isnan(e->latitude_deg));
  CHECK(std::isnan(e->roll_rad));
}

TEST_CASE("pose message: malformed datagrams are rejected with a reason") {
  std::string error;
  auto bad = [&](std::vector<std::uint8_t> bytes) {
    error.clear();
    return !decode_pose_message(bytes, error).has_value();
  };
  auto with = [](auto&& edit) {
    PoseMessage m = message(1);
    edit(m);
    const auto b = encode_pose_message(m);
    return std::vector<std::uint8_t>(b.begin(), b.end());
  };
  std::vector<std::uint8_t> v = kExampleDatagram;
  v.pop_back();
  CHECK(bad(v));
  CHECK_THAT(error, Contains("79 bytes, expected 80"));
  v = kExampleDatagram;
  v[3] = 'X';
  CHECK(bad(v));
  CHECK_THAT(error, Contains("bad magic 53 4C 50 58"));
  v = kExampleDatagram;
  v[4] = 2;
  CHECK(bad(v));
  CHECK_THAT(error, Contains("version 2 is not supported"));
  v = kExampleDatagram;
  v[6] = 81;
  CHECK(bad(v));
  CHECK_THAT(error, Contains("size field 81"));
  CHECK(bad(with([](PoseMessage& m) { m.latitude_deg = 91.0; })));
  CHECK_THAT(error, Contains("outside"));
  CHECK(bad(with([](PoseMessage& m) { m.longitude_deg = kNaN; })));
  CHECK_THAT(error, Contains("only one of latitude and longitude"));
  CHECK(bad(with([](PoseMessage& m) { m.depth_m = std::numeric_limits<double>::infinity(); })));
  CHECK(bad(with([](PoseMessage& m) { m.heading_rad = 90.0; })));  // degrees by mistake
  CHECK_THAT(error, Contains("radians"));
  CHECK_FALSE(bad(with([](PoseMessage& m) { m.heading_rad = -0.5; })));
}

// ---------------------------------------------------------------------------------------------
// UDP source
