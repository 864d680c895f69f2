#pragma once
// Sediment classes of APL-UW TR 9407 (1994) Table 2, as listed in docs/physics.md §2.2.
//
// Scenario files name sediments by `key` (snake_case) or one of its aliases. The acoustic
// parameters (ρ, ν, δ, σ2, γ, w2) live in sim/acoustics/apl_sediment.h: rock, cobble and
// gravel rows are table constants, every other row follows from its mean grain size Mz through
// TR 9407 Eqs. 2-10.
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace sonarloop::seabed {

// Index into sediment_table(); stable across versions (ids are never reused).
using SedimentId = int;

struct SedimentInfo {
  std::string_view key;         // YAML name, e.g. "very_fine_sand"
  std::string_view table_name;  // TR 9407 Table 2 name, e.g. "Very fine sand"
  std::string_view aliases;     // comma-separated other accepted names ("" if none)
  // Mean grain size Mz in φ units; empty for the rock/cobble rows, whose parameters are
  // table constants rather than grain-size regressions.
  std::optional<double> mz_phi;
};

// All rows of Table 2, roughest first.
std::span<const SedimentInfo> sediment_table();

// Looks a sediment up by key or alias (case-insensitive; spaces, '-' and '_' are equivalent).
std::optional<SedimentId> find_sediment(std::string_view name);

// "rough_rock, rock, cobble, ..." for error messages.
std::string sediment_keys_list();

}  // namespace sonarloop::seabed
