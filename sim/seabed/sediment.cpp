#include "sim/seabed/sediment.h"

#include <array>
#include <cctype>

namespace sonarloop::seabed {
namespace {

// docs/physics.md §2.2 (TR 9407 Table 2). Order is the id: append only.
constexpr std::array<SedimentInfo, 23> kTable{{
    {"rough_rock", "Rough rock", "", std::nullopt},
    {"rock", "Rock", "", std::nullopt},
    {"cobble", "Cobble", "gravel,pebble", std::nullopt},
    {"sandy_gravel", "Sandy gravel", "", -1.0},
    {"very_coarse_sand", "Very coarse sand", "", -0.5},
    {"muddy_sandy_gravel", "Muddy sandy gravel", "", 0.0},
    {"coarse_sand", "Coarse sand", "gravelly_sand", 0.5},
    {"gravelly_muddy_sand", "Gravelly muddy sand", "", 1.0},
    {"medium_sand", "Medium sand", "sand", 1.5},
    {"muddy_gravel", "Muddy gravel", "", 2.0},
    {"fine_sand", "Fine sand", "silty_sand", 2.5},
    {"muddy_sand", "Muddy sand", "", 3.0},
    {"very_fine_sand", "Very fine sand", "", 3.5},
    {"clayey_sand", "Clayey sand", "", 4.0},
    {"coarse_silt", "Coarse silt", "", 4.5},
    {"sandy_silt", "Sandy silt", "gravelly_mud", 5.0},
    {"medium_silt", "Medium silt", "sand_silt_clay", 5.5},
    {"sandy_mud", "Sandy mud", "", 6.0},
    {"fine_silt", "Fine silt", "clayey_silt", 6.5},
    {"sandy_clay", "Sandy clay", "", 7.0},
    {"very_fine_silt", "Very fine silt", "", 7.5},
    {"silty_clay", "Silty clay", "", 8.0},
    {"clay", "Clay", "", 9.0},
}};

// lower case; ' ' and '-' become '_'
std::string normalise(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (char ch : s) {
    if (ch == ' ' || ch == '-') ch = '_';
    out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(ch))));
  }
  return out;
}

bool alias_matches(std::string_view aliases, std::string_view name) {
  while (!aliases.empty()) {
    const auto comma = aliases.find(',');
    if (aliases.substr(0, comma) == name) return true;
    if (comma == std::string_view::npos) break;
    aliases.remove_prefix(comma + 1);
  }
  return false;
}

}  // namespace

std::span<const SedimentInfo> sediment_table() {
  return kTable;
}

std::optional<SedimentId> find_sediment(std::string_view name) {
  const std::string n = normalise(name);
  for (std::size_t i = 0; i < kTable.size(); ++i) {
    if (kTable[i].key == n || alias_matches(kTable[i].aliases, n)) {
      return static_cast<SedimentId>(i);
    }
  }
  return std::nullopt;
}

std::string sediment_keys_list() {
  std::string out;
  for (const auto& s : kTable) {
    if (!out.empty()) out += ", ";
    out += s.key;
  }
  return out;
}

}  // namespace sonarloop::seabed
