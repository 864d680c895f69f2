#pragma once
// Random target layouts for surveys (ours; issue 24): the same seabed with its targets placed
// afresh, so that a detector or a classifier is trained on some layouts and reported on others.
//
// random_layout keeps the scenario's seabed, water, sonar and vehicle and replaces its targets by
// one of each entry of `types`, in that order, each at a uniformly random position inside `area`
// (north, east) at least min_separation_m from every target placed before it (up to
// kMaxLayoutTries draws per target, then an error), with a uniformly random heading; named
// "<type>-<n>". A pure function of (layout_seed, the arguments). repeat_types(types, k) lists
// each type k times, round by round (k rounds of `types`).
#include <cstdint>
#include <vector>

#include "autonomy/survey.h"
#include "sim/scenario.h"
#include "sim/targets/target_type.h"

namespace sonarloop::mission {

inline constexpr int kMaxLayoutTries = 10000;

// Throws std::invalid_argument when a target cannot be placed (the area is too small for that
// many targets that far apart) or an argument is out of range.
Scenario random_layout(const Scenario& base, std::uint64_t layout_seed,
                       const std::vector<targets::TargetType>& types,
                       const autonomy::SurveyArea& area, double min_separation_m);

std::vector<targets::TargetType> repeat_types(const std::vector<targets::TargetType>& types, int k);

// The types of a scenario's targets, in its order (to draw its targets afresh).
std::vector<targets::TargetType> target_types_of(const Scenario& s);

}  // namespace sonarloop::mission
