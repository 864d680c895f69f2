// Contact JSON lines read back, the decision margin, the fusion rule and the final states.
#include <catch2/catch.hpp>

#include <cmath>

#include "atr/contact.h"
#include "autonomy/contact_decision.h"
#include "autonomy/json_line.h"

using namespace sonarloop;
using namespace sonarloop::autonomy;

namespace {

atr::Contact look(const std::string& cls, std::vector<std::pair<std::string, double>> scores,
                  bool mine_like) {
  atr::Contact c;
  c.id = 1;
  c.class_name = cls;
  c.mine_like = mine_like;
  c.scores = std::move(scores);
  std::sort(c.scores.begin(), c.scores.end(),
            [](const auto& a, const auto& b) { return a.second < b.second; });
  c.distance = c.scores[0].second;
  c.runner_up = c.scores[1].first;
  c.runner_up_distance = c.scores[1].second;
  c.mine_distance = c.non_mine_distance = std::nan("");
  return c;
}

}  // namespace

TEST_CASE("a contact line of the onboard consumer reads back") {
  atr::Contact c;
  c.id = 12;
  c.ping_number = 300;
  c.side = 0;
  c.north_m = -29.5;
  c.east_m = 10.25;
  c.ground_range_m = 21.0;
  c.class_name = "manta";
  c.mine_like = true;
  c.distance = 43.2;
  c.runner_up = "rockan";
  c.runner_up_distance = 45.1;
  c.scores = {{"manta", 43.2}, {"rockan", 45.1}, {"box", 50.0}};
  c.looks = 2;
  c.object = 4;
  c.fused_class = "manta";
  c.fused_mine_like = true;
  c.open_set_score = 0.8;
  std::string error;
  const auto r = contact_from_json(atr::contact_json(c), error);
  REQUIRE(r);
  CHECK(r->id == 12);
  CHECK(r->side == 0);
  CHECK(r->north_m == Approx(-29.5));
  CHECK(r->east_m == Approx(10.25));
  CHECK(r->ground_range_m == Approx(21.0));
  CHECK(r->class_name == "manta");
  CHECK(r->mine_like);
  CHECK(r->runner_up_distance == Approx(45.1));
  CHECK(r->scores.size() == 3);
  CHECK(r->looks == 2);
  CHECK(r->object == 4);
  CHECK(r->fused_class == "manta");
  REQUIRE(r->open_set_score);
  CHECK(*r->open_set_score == Approx(0.8));
  CHECK_FALSE(contact_from_json("{\"contact\":1}", error));
  CHECK_FALSE(contact_from_json("not json", error));
  CHECK_FALSE(contact_from_json("{\"contact\":1,\"north_m\":2,\"east_m\":3", error));
}

TEST_CASE("JsonLine reads strings with escapes and nested values") {
  std::string error;
  const auto j =
      JsonLine::parse(R"( {"a":"x\"y","b":[1,{"c":"]"}],"d":{"e":-1.5e2},"f":null} )", error);
  REQUIRE(j);
  CHECK(j->string("a") == "x\"y");
  CHECK(j->members().at("b") == R"([1,{"c":"]"}])");
  CHECK(j->object("d")->number("e") == Approx(-150.0));
  CHECK(j->has("f"));
  CHECK_FALSE(j->present("f"));
  CHECK_FALSE(j->number("a"));
}

TEST_CASE("the decision margin is the runner-up's normalised gap, or the open-set score's") {
  atr::Contact c = look("manta", {{"manta", 40.0}, {"rockan", 44.0}, {"box", 50.0}}, true);
  CHECK(decision_margin(c) == Approx(0.1));
  c.open_set_score = 0.95;
  CHECK(decision_margin(c) == Approx(0.05));
  c.open_set_score = 1.2;  // unknown object
  CHECK(decision_margin(c) == 0.0);
  atr::Contact none;
  CHECK(decision_margin(none) == 0.0);
}

TEST_CASE("looks fuse by the sum of normalised distances") {
  // look 1 barely prefers rockan; look 2 clearly prefers manta: the sum picks manta
  const atr::Contact a = look("rockan", {{"manta", 41.0}, {"rockan", 40.0}, {"box", 45.0}}, true);
  const atr::Contact b = look("manta", {{"manta", 30.0}, {"rockan", 36.0}, {"box", 38.0}}, true);
  const FusedDecision f = fuse_looks({a, b});
  CHECK(f.looks == 2);
  CHECK(f.class_name == "manta");
  CHECK(f.mine_like);
  const double ma = 42.0, mb = 104.0 / 3.0;  // the looks' mean distances
  const double d_manta = 41.0 / ma + 30.0 / mb, d_rockan = 40.0 / ma + 36.0 / mb;
  CHECK(f.margin == Approx((d_rockan - d_manta) / d_manta));
  CHECK_FALSE(f.from_onboard);
  // the onboard consumer's own fusion wins for the class
  atr::Contact b2 = b;
  b2.looks = 2;
  b2.fused_class = "box";
  b2.fused_mine_like = false;
  const FusedDecision g = fuse_looks({a, b2});
  CHECK(g.class_name == "box");
  CHECK_FALSE(g.mine_like);
  CHECK(g.from_onboard);
}

TEST_CASE("final states: confirmed by margin or by agreeing looks, else uncertain") {
  const atr::Contact sure = look("manta", {{"manta", 30.0}, {"rockan", 40.0}}, true);
  const atr::Contact unsure = look("manta", {{"manta", 40.0}, {"rockan", 40.4}}, true);
  const atr::Contact other = look("rockan", {{"manta", 40.4}, {"rockan", 40.0}}, true);
  CHECK(decide({sure}, 0.05).state == FinalState::kConfirmed);
  CHECK(decide({unsure}, 0.05).state == FinalState::kUncertain);
  // two agreeing looks confirm even below the threshold
  const ObjectDecision agree = decide({unsure, unsure}, 0.5);
  CHECK(agree.state == FinalState::kConfirmed);
  CHECK(agree.fused.class_name == "manta");
  CHECK(agree.fused.looks == 2);
  // disagreeing looks with a small fused margin stay uncertain
  CHECK(decide({unsure, other}, 0.05).state == FinalState::kUncertain);
  // a majority of at least two decides; a tie does not
  CHECK(decide({unsure, other, unsure}, 0.5).state == FinalState::kConfirmed);
  CHECK(decide({unsure, other, unsure, other}, 0.5).state == FinalState::kUncertain);
  // an unclassified look alone is uncertain
  atr::Contact bare;
  bare.status = "no_model";
  CHECK(decide({bare}, 0.05).state == FinalState::kUncertain);
  CHECK(std::string(to_string(FinalState::kConfirmed)) == "confirmed");
}

TEST_CASE("JsonLine reads arrays of objects, also from pretty JSON") {
  std::string error;
  const auto j = JsonLine::parse(
      "{\n  \"xs\": [\n    {\"a\": 1},\n    {\"a\": 2}\n  ],\n  \"n\": 3\n}", error);
  REQUIRE(j);
  const auto xs = j->objects("xs");
  REQUIRE(xs.size() == 2);
  CHECK(xs[1].number("a") == Approx(2.0));
  CHECK(j->number("n") == Approx(3.0));
  CHECK(j->objects("n").empty());
}

TEST_CASE("the mine margin is the two groups' relative gap, over the looks") {
  atr::Contact a = look("hemisphere", {{"hemisphere", 40.0}, {"manta", 50.0}}, false);
  a.non_mine_distance = 40.0;
  a.mine_distance = 50.0;
  CHECK(decide({a}, 0.05).fused.mine_margin == Approx(0.25));
  // two looks: each normalised by its mean distance (45 and 30), then summed
  atr::Contact b = look("hemisphere", {{"hemisphere", 27.0}, {"manta", 33.0}}, false);
  b.non_mine_distance = 27.0;
  b.mine_distance = 33.0;
  const double non_mine = 40.0 / 45.0 + 27.0 / 30.0, mine = 50.0 / 45.0 + 33.0 / 30.0;
  CHECK(decide({a, b}, 0.05).fused.mine_margin == Approx((mine - non_mine) / non_mine));
  // without the groups: unknown
  const atr::Contact bare = look("hemisphere", {{"hemisphere", 40.0}, {"manta", 50.0}}, false);
  CHECK(std::isnan(decide({bare}, 0.05).fused.mine_margin));
}

TEST_CASE("a contact line out of range is refused with the reason (the line is untrusted input)") {
  const std::string ok = R"({"contact":3,"north_m":1.5,"east_m":-2.0,"looks":2,"object":1})";
  std::string error;
  REQUIRE(contact_from_json(ok, error));
  const auto refused = [](const std::string& line, const std::string& why) {
    std::string e;
    INFO(line);
    CHECK_FALSE(contact_from_json(line, e));
    CHECK_THAT(e, Catch::Contains(why));
  };
  // 1e999 reads as infinity: the contact format writes non-finite values as null
  refused(R"({"contact":3,"north_m":1e999,"east_m":0})", "north_m is not a finite number");
  refused(R"({"contact":3,"north_m":0,"east_m":0,"distance":-1e999})",
          "distance is not a finite number");
  refused(R"({"contact":3,"north_m":0,"east_m":0,"scores":{"manta":1e999}})",
          "score manta is not a finite number");
  refused(R"({"contact":-15,"north_m":0,"east_m":0})", "contact is not an id");
  refused(R"({"contact":0,"north_m":0,"east_m":0})", "contact is not an id");
  refused(R"({"contact":2.5,"north_m":0,"east_m":0})", "contact is not an id");
  refused(R"({"contact":1e18,"north_m":0,"east_m":0})", "contact is not an id");
  refused(R"({"contact":3,"north_m":0,"east_m":0,"object":-1})", "object is not an id");
  refused(R"({"contact":3,"north_m":2e6,"east_m":0})", "north_m is more than 1000 km");
  refused(R"({"contact":3,"north_m":0,"east_m":0,"time_utc_ns":-5})", "time_utc_ns is not from");
  // the fuzzer's first finding: a time beyond what 64 bits hold
  refused(R"({"contact":3,"north_m":0,"east_m":0,"time_utc_ns":1.7e55})", "time_utc_ns is not");
  refused(R"({"contact":3,"north_m":0,"east_m":0,"ping":5e9})", "ping is not a whole number");
  refused(R"({"contact":3,"north_m":0,"east_m":0,"ping":-1})", "ping is not a whole number");
  refused(R"({"contact":3,"north_m":0,"east_m":0,"looks":0})", "looks is not a whole number");
  refused(R"({"contact":3,"north_m":0,"east_m":0,"looks":5000})", "looks is not a whole number");
}
