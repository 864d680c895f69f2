// Contacts as IMC (atr/imc_contacts.h): the map feature of a contact (name, colour, position),
// none without a position, and the sender over a real UDP socket on 127.0.0.1, read back with
// the project's decoder.
#include "atr/imc_contacts.h"

#include <catch2/catch.hpp>
#include <vector>

#include "drivers/net/udp_receiver.h"
#include "units/angles.h"

using namespace sonarloop;

namespace {

atr::Contact located_contact() {
  atr::Contact c;
  c.id = 9;
  c.object = 7;
  c.looks = 2;
  c.latitude_deg = 59.9;
  c.longitude_deg = 10.75;
  c.class_name = "cylinder";
  c.fused_class = "manta";
  c.fused_mine_like = true;
  c.time_utc_ns = 1'767'225'600'000'000'000;
  return c;
}

}  // namespace

TEST_CASE("imc contacts: a point of interest named after the object, at the contact") {
  const auto e = atr::contact_map_event(located_contact());
  REQUIRE(e);
  CHECK(e->type == imc::CcuEvent::kMapFeatureAdded);
  REQUIRE(e->arg);
  const imc::MapFeature& f = *e->arg;
  CHECK(f.id == "c7 manta mine-like");  // the fused decision, the object's first contact
  CHECK(e->id == f.id);
  CHECK(f.feature_type == imc::MapFeature::kPointOfInterest);
  CHECK(f.rgb_red == 255);
  CHECK(f.rgb_green == 0);
  REQUIRE(f.feature.size() == 1);
  CHECK(f.feature[0].lat_rad == Approx(59.9 * kRadPerDeg));
  CHECK(f.feature[0].lon_rad == Approx(10.75 * kRadPerDeg));

  atr::Contact one = located_contact();
  one.object = 0;  // a first look
  one.fused_class.clear();
  one.class_name = "rock";
  one.mine_like = false;
  const auto rock = atr::contact_map_event(one);
  REQUIRE(rock);
  CHECK(rock->arg->id == "c9 rock");
  CHECK(rock->arg->rgb_green == 200);  // yellow: not mine-like

  atr::Contact unclassified = one;
  unclassified.class_name.clear();
  CHECK(atr::contact_map_event(unclassified)->arg->id == "c9");
  CHECK(atr::contact_map_event(unclassified)->arg->rgb_blue == 128);

  atr::Contact local = one;
  local.latitude_deg.reset();
  local.longitude_deg.reset();
  CHECK_FALSE(atr::contact_map_event(local));
}

TEST_CASE("imc contacts: sent over UDP, one packet per located contact") {
  net::UdpReceiver rx(net::HostPort{"127.0.0.1", 0});
  atr::ImcContactSender sender(net::HostPort{"127.0.0.1", rx.bound_port()}, 0x2051);
  CHECK(sender.send(located_contact()));
  atr::Contact local = located_contact();
  local.latitude_deg.reset();
  CHECK_FALSE(sender.send(local));
  CHECK(sender.sent() == 1);
  CHECK(sender.without_position() == 1);
  CHECK_THAT(sender.describe(), Catch::Contains("127.0.0.1"));

  std::vector<std::uint8_t> buf(70000);
  const auto d = rx.receive(buf, 2000);
  REQUIRE(d);
  imc::Packet p;
  REQUIRE(imc::decode(std::span<const std::uint8_t>(buf.data(), d->datagram_size), p) ==
          imc::DecodeStatus::kOk);
  CHECK(p.mgid == imc::CcuEvent::kId);
  CHECK(p.header.src == 0x2051);
  CHECK(p.header.src_ent == imc::kImcEntityAtr);
  CHECK(p.header.timestamp_s == Approx(1767225600.0));
  const auto& e = std::get<imc::CcuEvent>(p.message);
  REQUIRE(e.arg);
  CHECK(e.arg->id == "c7 manta mine-like");
  CHECK_FALSE(rx.receive(buf, 200));  // nothing for the contact without a position
}
