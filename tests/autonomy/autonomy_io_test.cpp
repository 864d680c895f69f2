// The agent's wires (autonomy/autonomy_io.h) over real UDP on 127.0.0.1: the pose it publishes
// is the pose message the emulator reads (drivers/pose/pose_message.h), at the vehicle's place;
// the contacts it listens for arrive whole, a malformed datagram counted and dropped. The
// navigation from CAN is flown end to end in tests/tools/mission_cli_test.cpp (socketcand).
#include "autonomy/autonomy_io.h"

#include <array>
#include <catch2/catch.hpp>
#include <chrono>
#include <string>
#include <thread>

#include "drivers/pose/pose_message.h"

using namespace sonarloop;

namespace {

const GeoPoint kOrigin{59.9, 10.75};

// Polls `done` every 5 ms for up to 20 s (a bound against hangs, not a timing assertion).
template <class F>
bool wait_until(F done) {
  for (int i = 0; i < 4000 && !done(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  return done();
}

}  // namespace

TEST_CASE("autonomy io: the published pose is the emulator's pose message, at the vehicle") {
  net::UdpReceiver rx(net::parse_host_port("127.0.0.1:0"));
  const LocalTangentPlane ltp(kOrigin);
  autonomy::PosePublisher pose(net::parse_host_port("127.0.0.1:" + std::to_string(rx.bound_port())),
                               ltp);
  autonomy::VehicleState s;
  s.position = {120.0, -35.5};
  s.depth_m = 17.25;
  s.heading_rad = 0.75;
  s.pitch_rad = -0.05;
  pose.publish(s, 1'767'225'600'000'000'000);
  pose.publish(s, 1'767'225'600'100'000'000);
  CHECK(pose.sent() == 2);
  std::array<std::uint8_t, 256> buffer{};
  for (std::uint32_t expected = 1; expected <= 2; ++expected) {
    const auto got = rx.receive(buffer, 20000);
    REQUIRE(got);
    std::string error;
    const auto m = pose::decode_pose_message(std::span(buffer.data(), got->size), error);
    INFO(error);
    REQUIRE(m);
    CHECK(m->sequence == expected);
    const Vec2 ne = ltp.to_local(GeoPoint{m->latitude_deg, m->longitude_deg});
    CHECK(ne.x() == Approx(120.0).margin(1e-6));
    CHECK(ne.y() == Approx(-35.5).margin(1e-6));
    CHECK(m->depth_m == 17.25);
    CHECK(m->heading_rad == 0.75);
    CHECK(m->pitch_rad == -0.05);
    CHECK(m->roll_rad == 0.0);
  }
}

TEST_CASE("autonomy io: contacts arrive whole; a malformed datagram is counted, not taken") {
  autonomy::ContactListener contacts(net::parse_host_port("127.0.0.1:0"));
  REQUIRE(contacts.port() != 0);
  net::UdpSender tx(net::parse_host_port("127.0.0.1:" + std::to_string(contacts.port())));
  atr::Contact c;
  c.id = 42;
  c.ping_number = 1234;
  c.north_m = 10.5;
  c.east_m = -3.25;
  c.class_name = "manta";
  const std::string line = atr::contact_json(c);
  const std::string junk = "{\"not\": a contact";
  tx.send(std::span(reinterpret_cast<const std::uint8_t*>(junk.data()), junk.size()));
  tx.send(std::span(reinterpret_cast<const std::uint8_t*>(line.data()), line.size()));
  REQUIRE(wait_until([&] { return contacts.received() + contacts.malformed() == 2; }));
  CHECK(contacts.received() == 1);
  CHECK(contacts.malformed() == 1);
  const auto taken = contacts.take();
  REQUIRE(taken.size() == 1);
  CHECK(taken[0].id == 42);
  CHECK(taken[0].ping_number == 1234);
  CHECK(taken[0].north_m == 10.5);
  CHECK(taken[0].east_m == -3.25);
  CHECK(taken[0].class_name == "manta");
  CHECK(contacts.take().empty());  // handed over once
}

TEST_CASE("autonomy io: a burst is handed over a step's share at a time; a flood is bounded") {
  autonomy::ContactListener contacts(net::parse_host_port("127.0.0.1:0"));
  net::UdpSender tx(net::parse_host_port("127.0.0.1:" + std::to_string(contacts.port())));
  // 1000 more than kMaxQueuedContacts, nobody taking, in batches of 500 that the socket buffer
  // holds (each received before the next is sent: nothing is lost on the way)
  const std::size_t burst = autonomy::kMaxQueuedContacts + 1000;
  for (std::size_t k = 1; k <= burst; ++k) {
    atr::Contact c;
    c.id = k;
    const std::string line = atr::contact_json(c);
    tx.send(std::span(reinterpret_cast<const std::uint8_t*>(line.data()), line.size()));
    if (k % 500 == 0 || k == burst) REQUIRE(wait_until([&] { return contacts.received() == k; }));
  }
  CHECK(contacts.dropped() == 1000);
  std::size_t taken = 0;
  for (auto part = contacts.take(); !part.empty(); part = contacts.take()) {
    CHECK(part.size() <= autonomy::kMaxContactsPerTake);
    taken += part.size();
  }
  CHECK(taken == autonomy::kMaxQueuedContacts);
  CHECK(contacts.received() == taken + contacts.dropped());
}
