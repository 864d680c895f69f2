// Random target layouts (mission/layout.h): count, types, area, separation, determinism.
#include "mission/layout.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <map>

using namespace sonarloop;

namespace {

const std::vector<targets::TargetType> kTypes = {targets::TargetType::kManta,
                                                 targets::TargetType::kBox};
const autonomy::SurveyArea kArea{{-50.0, -30.0}, {50.0, 30.0}};

}  // namespace

TEST_CASE("random layout: per_type of each type, inside the area, apart, named, repeatable") {
  Scenario base;
  base.scene.targets.resize(3);  // replaced
  const Scenario s = mission::random_layout(base, 7, mission::repeat_types(kTypes, 5), kArea, 10.0);
  REQUIRE(s.scene.targets.size() == 10);
  std::map<targets::TargetType, int> count;
  for (std::size_t i = 0; i < s.scene.targets.size(); ++i) {
    const auto& t = s.scene.targets[i];
    ++count[t.type];
    CHECK(t.position_m.x() >= -50.0);
    CHECK(t.position_m.x() <= 50.0);
    CHECK(t.position_m.y() >= -30.0);
    CHECK(t.position_m.y() <= 30.0);
    CHECK(t.heading_deg >= 0.0);
    CHECK(t.heading_deg < 360.0);
    for (std::size_t j = 0; j < i; ++j)
      CHECK((t.position_m - s.scene.targets[j].position_m).norm() >= 10.0);
  }
  CHECK(count[targets::TargetType::kManta] == 5);
  CHECK(count[targets::TargetType::kBox] == 5);
  CHECK(s.scene.targets[0].name == "manta-1");
  CHECK(s.scene.targets[1].name == "box-1");
  const Scenario again =
      mission::random_layout(base, 7, mission::repeat_types(kTypes, 5), kArea, 10.0);
  const Scenario other =
      mission::random_layout(base, 8, mission::repeat_types(kTypes, 5), kArea, 10.0);
  CHECK(again.scene.targets[4].position_m == s.scene.targets[4].position_m);
  CHECK(other.scene.targets[4].position_m != s.scene.targets[4].position_m);
}

TEST_CASE("random layout: too many targets too far apart, or no area, is an error, not a hang") {
  CHECK_THROWS_AS(
      mission::random_layout(Scenario{}, 1, mission::repeat_types(kTypes, 50), kArea, 30.0),
      std::invalid_argument);
  CHECK(mission::random_layout(Scenario{}, 1, {}, kArea, 1.0).scene.targets.empty());
  CHECK_THROWS_AS(mission::random_layout(Scenario{}, 1, kTypes, {{1.0, 1.0}, {1.0, 2.0}}, 1.0),
                  std::invalid_argument);
}
