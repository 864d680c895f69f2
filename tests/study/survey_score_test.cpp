// Survey scoring (study/survey_score.h): coverage, one-to-one matching, false contacts, the
// pooled tables and the detector's FROC, on a flat scene with planted objects.
#include "study/survey_score.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "sim/seabed/sediment.h"
#include "sim/targets/target_type.h"

using namespace sonarloop;
using study::ScoredCandidate;
using study::StreamObject;
using study::SwathPing;

namespace {

constexpr double kMaxRange_m = 50.0;
constexpr double kAltitude_m = 7.5;

// Flat medium sand 200 m x 200 m; a Manta 20 m east of the line east = 0, a box 30 m west of it,
// and a cylinder 60 m east (beyond the swath).
scene::SceneDesc flat_scene() {
  scene::SceneDesc d;
  d.seed = 5;
  d.water.depth_m = 25.0;
  d.seabed.origin_m = Vec2(-100, -100);
  d.seabed.extent_m = Vec2(200, 200);
  d.seabed.grid_spacing_m = 0.1;
  d.seabed.elevation.rms_m = 0.0;
  scene::RegionDesc r;
  r.sediment = *seabed::find_sediment("medium_sand");
  d.seabed.regions = {r};
  const auto add = [&](targets::TargetType type, double n, double e, const char* name) {
    scene::TargetDesc t;
    t.type = type;
    t.position_m = Vec2(n, e);
    t.name = name;
    d.targets.push_back(t);
  };
  add(targets::TargetType::kManta, 0.0, 20.0, "manta-1");
  add(targets::TargetType::kBox, 10.0, -30.0, "box-1");
  add(targets::TargetType::kCylinder, 0.0, 60.0, "cylinder-1");
  return d;
}

// One line north along east = 0 from north -50 to 50, a ping every 0.1 m.
std::vector<SwathPing> line_pings() {
  std::vector<SwathPing> p;
  for (int i = 0; i <= 1000; ++i)
    p.push_back(SwathPing{0.1 * i, -50.0 + 0.1 * i, 0.0, 0.0, kAltitude_m});
  return p;
}

StreamObject object(std::uint64_t id, double n, double e, const std::string& cls, bool mine) {
  StreamObject o;
  o.id = id;
  o.north_m = n;
  o.east_m = e;
  o.looks = 1;
  o.class_name = cls;
  o.mine_like = mine;
  return o;
}

}  // namespace

TEST_CASE("survey score: coverage, matching, a planted miss and a planted false contact") {
  const scene::Scene scene(flat_scene());
  const std::vector<SwathPing> pings = line_pings();

  // both covered targets found, the Manta identified, the box called a Manta (mine: wrong side)
  std::vector<StreamObject> objects = {object(1, 0.5, 20.4, "manta", true),
                                       object(2, 9.0, -30.5, "manta", true)};
  const study::SurveyScore s = study::score_survey(scene, pings, kMaxRange_m, objects);
  REQUIRE(s.targets.size() == 3);
  CHECK(s.targets[0].covered);
  CHECK(s.targets[1].covered);
  CHECK_FALSE(s.targets[2].covered);  // 60 m out: beyond the 50 m range
  CHECK(s.targets[0].detected);
  CHECK(s.targets[0].identified);
  CHECK(s.targets[0].mine_correct);
  CHECK(s.targets[0].error_m == Approx(std::hypot(0.5, 0.4)));
  CHECK(s.targets[1].detected);
  CHECK_FALSE(s.targets[1].identified);
  CHECK_FALSE(s.targets[1].mine_correct);
  CHECK(s.false_contacts.empty());
  CHECK(s.targets[0].seabed == "flat");
  // the covered area: two bands from the nadir gap (the altitude) to the far edge less half a
  // chip, 100 m long (plus the band's ends), on a 1 m grid
  const double band_m =
      std::sqrt(kMaxRange_m * kMaxRange_m - kAltitude_m * kAltitude_m) - 1.5 - kAltitude_m;
  CHECK(s.area_km2 == Approx(2 * band_m * 100.0 * 1e-6).epsilon(0.05));
  CHECK(s.area_km2_by_kind.at("flat") == Approx(s.area_km2));

  study::SurveyTally tally;
  tally.add(s);
  const auto rows = study::survey_rows(tally);
  CHECK(rows[0].scope == "all");
  CHECK(rows[0].c.covered == 2);
  CHECK(rows[0].pd == Approx(1.0));
  CHECK(rows[0].identified == Approx(0.5));
  CHECK(rows[0].mine_error == Approx(0.5));
  CHECK(rows[0].c.false_contacts == 0);

  SECTION("a planted miss lowers the probability of detection") {
    objects.pop_back();
    const study::SurveyScore m = study::score_survey(scene, pings, kMaxRange_m, objects);
    CHECK_FALSE(m.targets[1].detected);
    study::SurveyTally t;
    t.add(m);
    CHECK(study::survey_rows(t)[0].pd == Approx(0.5));
    CHECK(study::survey_rows(t)[0].pd_ci.hi < 1.0);
  }
  SECTION("a planted false contact is counted, per km2 and per target") {
    objects.push_back(object(3, -20.0, 10.0, "rockan", true));
    const study::SurveyScore f = study::score_survey(scene, pings, kMaxRange_m, objects);
    REQUIRE(f.false_contacts.size() == 1);
    CHECK(f.false_contacts[0].object == 3);
    CHECK(f.false_contacts[0].class_name == "rockan");
    study::SurveyTally t;
    t.add(f);
    const auto r = study::survey_rows(t);
    CHECK(r[0].c.false_contacts == 1);
    CHECK(r[0].false_per_km2 == Approx(1.0 / f.area_km2));
    CHECK(r[0].false_per_target == Approx(1.0 / 3.0));
    CHECK(r[0].pd == Approx(1.0));
  }
  SECTION("matching is one to one: two objects at one target make one detection and one false") {
    objects.push_back(object(4, 0.0, 21.5, "manta", true));
    const study::SurveyScore d = study::score_survey(scene, pings, kMaxRange_m, objects);
    CHECK(d.targets[0].detected);
    CHECK(d.targets[0].error_m == Approx(std::hypot(0.5, 0.4)));  // the nearer one
    REQUIRE(d.false_contacts.size() == 1);
    CHECK(d.false_contacts[0].object == 4);
  }
  SECTION("an object beyond the match radius is a false contact, and the target missed") {
    objects[0].east_m = 20.0 + study::kSurveyMatchRadius_m + 0.1;
    objects[0].north_m = 0.0;
    const study::SurveyScore d = study::score_survey(scene, pings, kMaxRange_m, objects);
    CHECK_FALSE(d.targets[0].detected);
    CHECK(d.false_contacts.size() == 1);
  }
}

TEST_CASE("survey score: a target in the nadir gap is not covered") {
  scene::SceneDesc desc = flat_scene();
  desc.targets[0].position_m = Vec2(0.0, 5.0);  // 5 m across: inside the 7.5 m nadir gap
  const scene::Scene scene(desc);
  const study::SurveyScore s = study::score_survey(scene, line_pings(), kMaxRange_m, {});
  CHECK_FALSE(s.targets[0].covered);
  study::SurveyScoreOptions o;
  o.nadir_gap_m = 2.0;
  CHECK(study::score_survey(scene, line_pings(), kMaxRange_m, {}, o).targets[0].covered);
}

TEST_CASE("survey score: the objects of a contact stream are its looks grouped by object id") {
  atr::Contact a;
  a.id = 1;
  a.north_m = 1.0;
  a.east_m = 2.0;
  a.class_name = "rockan";
  a.mine_like = true;
  atr::Contact b;
  b.id = 2;
  b.north_m = 5.0;
  b.east_m = 5.0;
  b.status = "gap";
  atr::Contact c;  // a second look of object 1, fused to "manta"
  c.id = 3;
  c.object = 1;
  c.looks = 2;
  c.north_m = 2.0;
  c.east_m = 3.0;
  c.class_name = "rockan";
  c.fused_class = "manta";
  c.fused_mine_like = true;
  const std::vector<atr::Contact> contacts = {a, b, c};
  const std::vector<StreamObject> o = study::stream_objects(contacts);
  REQUIRE(o.size() == 2);
  CHECK(o[0].id == 1);
  CHECK(o[0].looks == 2);
  CHECK(o[0].north_m == Approx(1.5));
  CHECK(o[0].east_m == Approx(2.5));
  CHECK(o[0].class_name == "manta");
  CHECK(o[1].class_name.empty());
  CHECK(o[1].status == "gap");
}

TEST_CASE("survey score: the FROC from one pass over the candidates") {
  const scene::Scene scene(flat_scene());
  const study::SurveyScore s = study::score_survey(scene, line_pings(), kMaxRange_m, {});
  // the Manta seen twice (scores 0.4 and 0.15, 1 m apart: one object), the box once at 0.2, a
  // rock at 0.25, a suppressed fragment at 0.5 that must never count
  const std::vector<ScoredCandidate> c = {{0.0, 20.0, 0.4, true},
                                          {1.0, 20.0, 0.15, true},
                                          {10.0, -30.0, 0.2, true},
                                          {-30.0, 15.0, 0.25, true},
                                          {-30.5, 15.0, 0.5, false}};
  const std::vector<double> thresholds = {0.1, 0.2, 0.3, 0.5};
  const auto f = study::froc_counts(s, c, thresholds, 2.0, study::kSurveyMatchRadius_m);
  REQUIRE(f.size() == 4);
  CHECK(f[0].covered == 2);
  CHECK(f[0].detected == 2);
  CHECK(f[0].false_contacts == 1);
  CHECK(f[1].detected == 2);  // >= 0.2 keeps the box
  CHECK(f[1].false_contacts == 1);
  CHECK(f[2].detected == 1);  // >= 0.3: the Manta only, the rock gone
  CHECK(f[2].false_contacts == 0);
  CHECK(f[3].detected == 0);
  std::vector<study::FrocCounts> pooled;
  study::add_froc(pooled, f);
  study::add_froc(pooled, f);
  CHECK(pooled[0].covered == 4);
  CHECK(pooled[2].detected == 2);
  CHECK(study::froc_csv(pooled).find("0.2000,6,4,4,1.0000") != std::string::npos);
}
