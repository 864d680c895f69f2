// The onboard pipeline on a synthetic stream: objects come out as contacts at their true
// latitude/longitude (pitch and side accounted for), datagrams in any order; and once warmed up,
// the per-ping path (receive, decode, reorder, waterfall, detect) allocates nothing; a model's
// detector rules decide whether an object seen in one ping is reported.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <numbers>
#include <vector>

#include "atr/onboard_pipeline.h"
#include "tests/atr/synthetic_chips.h"
#include "tests/atr/synthetic_pings.h"
#include "tests/support/allocation_counter.h"

using namespace sonarloop;

namespace {

using Bytes = std::vector<std::uint8_t>;

const std::vector<testing::SeabedObject> kObjects = {
    {1, 10.0, 12.0, 0.8, 0.40}, {0, 20.0, 18.0, 1.0, 0.35}, {1, 30.0, 15.0, 0.8, 0.45}};

double pitch_deg(int k) {
  return 4.0 * std::sin(2.0 * std::numbers::pi * k * 0.0675 / 2.5);
}

std::vector<Bytes> stream(int pings, const std::vector<testing::SeabedObject>& objects = kObjects,
                          double (*pitch)(int) = pitch_deg) {
  const xtf::XtfFileHeader h = testing::make_stream_header();
  std::vector<Bytes> out{xtf::encode_file_header(h)};
  testing::stream_line(pings, objects, pitch, h,
                       [&](const xtf::XtfPing& p) { out.push_back(xtf::encode_ping(p, h)); });
  return out;
}

}  // namespace

TEST_CASE("onboard pipeline: synthetic objects reported at their latitude/longitude") {
  const std::vector<Bytes> datagrams = stream(300);
  for (const bool shuffled : {false, true}) {
    INFO((shuffled ? "pairs of datagrams swapped" : "in order"));
    std::vector<atr::Contact> contacts;
    atr::OnboardPipeline pipeline(std::nullopt, atr::OnboardOptions{},
                                  [&](const atr::Contact& c) { contacts.push_back(c); });
    for (std::size_t i = 0; i < datagrams.size(); ++i) {
      // swapped pairs: the receiver puts them back in order
      const std::size_t j = shuffled && i > 0 ? (i % 2 ? i + 1 : i - 1) : i;
      pipeline.feed(datagrams[std::min(j, datagrams.size() - 1)]);
    }
    pipeline.finish();
    REQUIRE(contacts.size() == kObjects.size());
    const LocalTangentPlane plane(testing::kStreamOrigin);
    for (std::size_t i = 0; i < kObjects.size(); ++i) {
      const atr::Contact& c = contacts[i];
      const testing::SeabedObject& o = kObjects[i];
      REQUIRE(c.latitude_deg);
      const Vec2 ne = plane.to_local(GeoPoint{*c.latitude_deg, *c.longitude_deg});
      // the detector's centre lies between the highlight and the shadow's start: near the
      // object's near edge, within a few decimetres
      const Vec2 truth(o.along_m, o.side == 1 ? o.ground_m : -o.ground_m);
      INFO("object " << i << " at " << truth.transpose() << ", contact at " << ne.transpose());
      CHECK((ne - truth).norm() < 0.3);
      CHECK(c.side == o.side);
      CHECK(c.status == "no_model");
      CHECK(c.class_name.empty());
      CHECK(c.time_utc_ns);
    }
    const atr::OnboardStats s = pipeline.stats();
    CHECK(s.contacts == kObjects.size());
    // swapped, ping 1 comes first and starts the sequence: ping 0 is then late (dropped)
    CHECK(s.receiver.pings == (shuffled ? 299 : 300));
    CHECK(s.receiver.late == (shuffled ? 1 : 0));
    CHECK(s.receiver.reordered == (shuffled ? 149 : 0));
  }
}

TEST_CASE("onboard pipeline: no allocation per ping once warmed up") {
  const std::vector<Bytes> datagrams = stream(400);
  long contacts = 0;
  atr::OnboardPipeline pipeline(std::nullopt, atr::OnboardOptions{},
                                [&](const atr::Contact&) { ++contacts; });
  // warm-up: the header, the first ping sizes the waterfall and the detector, the reorder slots
  // and the receiver's scratch ping fill up
  const std::size_t warm = 60;
  const long warm_up = testing::allocations_in([&] {
    for (std::size_t i = 0; i < warm; ++i)
      pipeline.feed(datagrams[i]);
  });
  CHECK(warm_up > 0);  // the counter counts: sizing the buffers allocates
  const long per_ping = testing::allocations_in([&] {
    for (std::size_t i = warm; i < datagrams.size(); ++i)
      pipeline.feed(datagrams[i]);
  });
  CHECK(per_ping == 0);
  // the counted stretch held objects, so the detector's paths ran (and reported them)
  CHECK(contacts >= 2);
  CHECK(pipeline.stats().receiver.pings > 300);
}

TEST_CASE("onboard pipeline: the model's detector rules decide an object seen in one ping") {
  // one object 0.1 m long, at ping 40's footprint (0.135 m between pings, no pitch): one ping
  // sees it
  const std::vector<testing::SeabedObject> one_ping = {{1, 40 * 0.135, 12.0, 0.1, 0.40}};
  const std::vector<Bytes> datagrams = stream(150, one_ping, [](int) { return 0.0; });
  // a small two-class model (no gates, no clutter class): every object it sees is reported
  const atr::Model plain = testing::small_two_class_model();
  atr::Model single = plain;
  single.detector_rules = atr::DetectorRules{1, 0.0};
  const auto contacts_with = [&](std::optional<atr::Model> model) {
    std::vector<atr::Contact> out;
    atr::OnboardPipeline pipeline(std::move(model), atr::OnboardOptions{},
                                  [&](const atr::Contact& c) { out.push_back(c); });
    for (const Bytes& d : datagrams)
      pipeline.feed(d);
    pipeline.finish();
    return out;
  };
  // the detector's defaults (two pings at least) reject it, with or without a model that records
  // no rules
  CHECK(contacts_with(std::nullopt).empty());
  CHECK(contacts_with(plain).empty());
  // a model trained behind a one-ping detector reports it, where it is
  const std::vector<atr::Contact> seen = contacts_with(single);
  REQUIRE(seen.size() == 1);
  CHECK(seen[0].side == 1);
  REQUIRE(seen[0].latitude_deg);
  const LocalTangentPlane plane(testing::kStreamOrigin);
  const Vec2 ne = plane.to_local(GeoPoint{*seen[0].latitude_deg, *seen[0].longitude_deg});
  CHECK((ne - Vec2(40 * 0.135, 12.0)).norm() < 0.3);
}
