#pragma once
// Target materials: density and compressional sound speed, whose product is the acoustic
// impedance Z = ρ·c used for the target reflectance (docs/physics.md §4, impedance table).
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace sonarloop::targets {

struct NamedMaterial {
  std::string_view key;  // YAML name
  double density_kg_m3;
  double sound_speed_m_s;
};

// steel, aluminium, concrete, grp, rubber (docs/physics.md §4).
std::span<const NamedMaterial> material_table();
std::optional<NamedMaterial> find_material(std::string_view key);
std::string material_keys_list();

}  // namespace sonarloop::targets
