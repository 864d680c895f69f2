#include "sim/targets/target_type.h"

#include <array>

namespace sonarloop::targets {
namespace {

const std::array<TargetTypeInfo, 9>& table() {
  static const std::array<TargetTypeInfo, 9> kTable{{
      {TargetType::kManta, "manta", "Manta", {0.98, 0.98, 0.47}, true},
      {TargetType::kRockan, "rockan", "Rockan", {1.00, 0.50, 0.40}, true},
      {TargetType::kCylinder, "cylinder", "Cylinder", {1.00, 0.30, 0.30}, true},
      {TargetType::kStandingCylinder,
       "standing_cylinder",
       "Standing cylinder",
       {0.30, 0.30, 1.00},
       false},
      {TargetType::kCuboid, "cuboid", "Cuboid", {1.00, 0.30, 0.30}, true},
      {TargetType::kLargeCuboid, "large_cuboid", "Large cuboid", {1.00, 0.50, 0.40}, false},
      {TargetType::kHemisphere, "hemisphere", "Hemisphere", {1.00, 1.00, 0.50}, false},
      {TargetType::kSmallHemisphere,
       "small_hemisphere",
       "Small hemisphere",
       {0.50, 0.50, 0.25},
       false},
      {TargetType::kBox, "box", "Box", {0.70, 0.70, 0.40}, false},
  }};
  return kTable;
}

}  // namespace

std::span<const TargetTypeInfo> target_type_table() {
  return table();
}

const TargetTypeInfo& target_type_info(TargetType t) {
  return table()[static_cast<int>(t)];
}

std::optional<TargetType> find_target_type(std::string_view key) {
  for (const auto& info : table()) {
    if (info.key == key) return info.type;
  }
  return std::nullopt;
}

std::string target_type_keys_list() {
  std::string out;
  for (const auto& info : table()) {
    if (!out.empty()) out += ", ";
    out += info.key;
  }
  return out;
}

}  // namespace sonarloop::targets
