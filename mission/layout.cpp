#include "mission/layout.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "common/rng.h"

namespace sonarloop::mission {

std::vector<targets::TargetType> repeat_types(const std::vector<targets::TargetType>& types,
                                              int k) {
  std::vector<targets::TargetType> out;
  for (int i = 0; i < k; ++i)
    out.insert(out.end(), types.begin(), types.end());
  return out;
}

std::vector<targets::TargetType> target_types_of(const Scenario& s) {
  std::vector<targets::TargetType> out;
  for (const scene::TargetDesc& t : s.scene.targets)
    out.push_back(t.type);
  return out;
}

Scenario random_layout(const Scenario& base, std::uint64_t layout_seed,
                       const std::vector<targets::TargetType>& types,
                       const autonomy::SurveyArea& area, double min_separation_m) {
  if (!(area.max.north_m > area.min.north_m && area.max.east_m > area.min.east_m)) {
    throw std::invalid_argument("random layout: the area is empty");
  }
  if (!(min_separation_m >= 0.0 && std::isfinite(min_separation_m))) {
    throw std::invalid_argument("random layout: min separation must be >= 0 m");
  }
  Scenario s = base;
  s.scene.targets.clear();
  Rng rng(layout_seed, RngStream::kLayout);
  std::map<targets::TargetType, int> count;
  {
    for (const targets::TargetType type : types) {
      bool placed = false;
      for (int tries = 0; tries < kMaxLayoutTries && !placed; ++tries) {
        const double n = rng.uniform(area.min.north_m, area.max.north_m);
        const double e = rng.uniform(area.min.east_m, area.max.east_m);
        bool free = true;
        for (const scene::TargetDesc& t : s.scene.targets) {
          free = free && std::hypot(t.position_m.x() - n, t.position_m.y() - e) >= min_separation_m;
        }
        if (!free) continue;
        scene::TargetDesc t;
        t.type = type;
        t.position_m = Vec2(n, e);
        t.heading_deg = rng.uniform(0.0, 360.0);
        t.name =
            std::string(targets::target_type_info(type).key) + "-" + std::to_string(++count[type]);
        s.scene.targets.push_back(t);
        placed = true;
      }
      if (!placed) {
        throw std::invalid_argument("random layout: cannot place " + std::to_string(types.size()) +
                                    " targets " + std::to_string(min_separation_m) +
                                    " m apart in the area");
      }
    }
  }
  return s;
}

}  // namespace sonarloop::mission
