#pragma once
// One lock-step mission per seed (mission/lockstep.h), scored against the scene's truth
// (study/survey_score.h): what `sonarloop mission` runs for each of its seeds.
#include <cstdint>
#include <memory>
#include <optional>

#include "atr/onboard_pipeline.h"
#include "atr/subspace_classifier.h"
#include "autonomy/agent.h"
#include "mission/agent_setup.h"
#include "mission/lockstep.h"
#include "sim/scenario.h"
#include "study/survey_score.h"

namespace sonarloop::mission {

struct MissionSpec {
  Scenario scenario;
  // draw the targets afresh for each seed (mission/layout.h: the scenario's types, anywhere in
  // the survey area, at least layout_separation_m apart; layout seed = the seed): surveys of
  // layouts a method was not tuned on
  bool random_layout = false;
  double layout_separation_m = 25.0;
  std::optional<atr::Model> model;  // none: contacts unclassified
  atr::OnboardOptions onboard;
  AgentOverrides agent;
  LockstepOptions lockstep;
  study::SurveyScoreOptions score;
  // the detector's thresholds (height, m) of the FROC: from its floor up
  std::vector<double> froc_thresholds = default_froc_thresholds();
  static std::vector<double> default_froc_thresholds();
  // the classification gate's thresholds (probabilities) of its FROC
  std::vector<double> gate_thresholds = default_gate_thresholds();
  static std::vector<double> default_gate_thresholds();
};

struct SeedRun {
  std::uint64_t seed = 0;
  Scenario scenario;  // as flown (seed, layout)
  AgentSetup setup;
  std::unique_ptr<autonomy::Agent> agent;  // its objects, re-looks and track after the mission
  LockstepResult run;
  std::vector<study::StreamObject> objects;  // of the contact stream
  study::SurveyScore score;
  std::vector<study::FrocCounts> detector_froc;  // at MissionSpec::froc_thresholds
  // the classification gate's FROC (the detector and detection gate at their thresholds), at
  // MissionSpec::gate_thresholds; empty without a classification gate
  std::vector<study::FrocCounts> gate_froc;
};

// Flies the mission of `spec` with the scene's seed replaced by `seed` (its seabed, clutter,
// speckle and navigation errors; the targets stay where the scenario puts them unless
// random_layout) and scores it.
SeedRun run_seed(const MissionSpec& spec, std::uint64_t seed, const LockstepHooks& hooks = {});

}  // namespace sonarloop::mission
