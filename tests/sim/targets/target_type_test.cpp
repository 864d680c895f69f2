#include "sim/targets/target_type.h"

#include <catch2/catch.hpp>
#include <set>
#include <string>

using namespace sonarloop::targets;
using sonarloop::Vec3;

TEST_CASE("target_type: nominal sizes match the issue (Pailhas et al. 2010, Sec. 2.2)") {
  // length (along heading) x width x height, m
  const std::pair<TargetType, Vec3> expected[] = {
      {TargetType::kManta, {0.98, 0.98, 0.47}},
      {TargetType::kRockan, {1.00, 0.50, 0.40}},
      {TargetType::kCylinder, {1.00, 0.30, 0.30}},
      {TargetType::kStandingCylinder, {0.30, 0.30, 1.00}},
      {TargetType::kCuboid, {1.00, 0.30, 0.30}},
      {TargetType::kLargeCuboid, {1.00, 0.50, 0.40}},
      {TargetType::kHemisphere, {1.00, 1.00, 0.50}},
      {TargetType::kSmallHemisphere, {0.50, 0.50, 0.25}},
      {TargetType::kBox, {0.70, 0.70, 0.40}},
  };
  REQUIRE(target_type_table().size() == std::size(expected));
  for (const auto& [type, size] : expected) {
    const auto& info = target_type_info(type);
    INFO(info.key);
    CHECK(info.type == type);
    CHECK((info.size_m - size).norm() < 1e-12);
  }
}

TEST_CASE("target_type: keys are unique and round-trip; ids are the table order") {
  std::set<std::string> keys;
  int id = 0;
  for (const auto& info : target_type_table()) {
    CHECK(static_cast<int>(info.type) == id++);
    CHECK(keys.insert(std::string(info.key)).second);
    const auto found = find_target_type(info.key);
    REQUIRE(found.has_value());
    CHECK(*found == info.type);
  }
  CHECK_FALSE(find_target_type("mantaray").has_value());
  CHECK(target_type_keys_list().find("small_hemisphere") != std::string::npos);
}

TEST_CASE("target_type: mine-like flags (Sec. 4.1.2)") {
  CHECK(target_type_info(TargetType::kManta).mine_like);
  CHECK(target_type_info(TargetType::kRockan).mine_like);
  CHECK(target_type_info(TargetType::kCylinder).mine_like);
  CHECK(target_type_info(TargetType::kCuboid).mine_like);
  CHECK_FALSE(target_type_info(TargetType::kHemisphere).mine_like);
  CHECK_FALSE(target_type_info(TargetType::kBox).mine_like);
}
