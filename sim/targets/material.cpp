#include "sim/targets/material.h"

#include <array>

namespace sonarloop::targets {
namespace {

// docs/physics.md §4, impedance reflectance table.
constexpr std::array<NamedMaterial, 5> kMaterials{{
    {"steel", 7850.0, 5900.0},
    {"aluminium", 2700.0, 6320.0},
    {"concrete", 2400.0, 3700.0},
    {"grp", 1800.0, 2500.0},
    {"rubber", 1100.0, 1600.0},
}};

}  // namespace

std::span<const NamedMaterial> material_table() {
  return kMaterials;
}

std::optional<NamedMaterial> find_material(std::string_view key) {
  for (const auto& m : kMaterials) {
    if (m.key == key) return m;
  }
  return std::nullopt;
}

std::string material_keys_list() {
  std::string out;
  for (const auto& m : kMaterials) {
    if (!out.empty()) out += ", ";
    out += m.key;
  }
  return out;
}

}  // namespace sonarloop::targets
