#pragma once
// The mine-like and non-mine targets of Pailhas et al. (2010), Section 2.2 and Fig. 12, with
// their nominal dimensions. Ids are stable (append only).
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "sim/frames.h"

namespace sonarloop::targets {

enum class TargetType : int {
  kManta = 0,             // truncated cone, 98 cm base, 49 cm top, 47 cm high
  kRockan = 1,            // 100 x 50 x 40 cm flattened angular shell (see rockan.h)
  kCylinder = 2,          // lying cylinder, 100 cm long, 30 cm diameter
  kStandingCylinder = 3,  // the same cylinder on its end
  kCuboid = 4,            // 100 x 30 x 30 cm
  kLargeCuboid = 5,       // 100 x 50 x 40 cm
  kHemisphere = 6,        // 100 cm diameter
  kSmallHemisphere = 7,   // 50 cm diameter
  kBox = 8,               // 70 x 70 x 40 cm
};

struct TargetTypeInfo {
  TargetType type;
  std::string_view key;   // YAML name
  std::string_view name;  // display name
  // Nominal size (m): length along the target's heading axis, width across it, height.
  Vec3 size_m;
  bool mine_like;  // Section 4.1.2: Manta, Rockan, cylinder, cuboid count as mine-like
};

std::span<const TargetTypeInfo> target_type_table();
const TargetTypeInfo& target_type_info(TargetType t);
std::optional<TargetType> find_target_type(std::string_view key);
std::string target_type_keys_list();

}  // namespace sonarloop::targets
