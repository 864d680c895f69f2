#include "mission/mission_run.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mission/layout.h"
#include "sim/render/sonar.h"
#include "sim/scene/scene.h"

namespace sonarloop::mission {

std::vector<double> MissionSpec::default_froc_thresholds() {
  std::vector<double> t;
  for (int i = 10; i <= 60; ++i)
    t.push_back(0.01 * i);
  return t;
}

std::vector<double> MissionSpec::default_gate_thresholds() {
  std::vector<double> t;
  for (int i = 0; i <= 100; ++i)
    t.push_back(0.01 * i);
  // finer towards 0, where a gate that keeps 98 % of the targets sits
  for (const double v : {0.001, 0.002, 0.005})
    t.push_back(v);
  std::sort(t.begin(), t.end());
  return t;
}

SeedRun run_seed(const MissionSpec& spec, std::uint64_t seed, const LockstepHooks& hooks) {
  SeedRun r;
  r.seed = seed;
  Scenario scenario = spec.scenario;
  scenario.scene.seed = seed;
  r.setup = make_agent_setup(scenario, spec.agent);
  if (spec.random_layout) {
    scenario = random_layout(scenario, seed, target_types_of(scenario), r.setup.area,
                             spec.layout_separation_m);
  }
  r.scenario = scenario;
  const scene::Scene scene(scenario.scene);
  r.agent = std::make_unique<autonomy::Agent>(r.setup.params, r.setup.survey, r.setup.start);
  r.run = run_lockstep(scenario, scene, spec.model, spec.onboard, *r.agent, spec.lockstep, hooks);
  r.objects = study::stream_objects(r.run.contacts);
  const render::SonarSetup sonar = render::make_sonar_setup(scenario.sonar, scenario.scene.water);
  const double max_range_m = static_cast<double>(sonar.bins) * sonar.desc.bin_size_m;
  r.score = study::score_survey(scene, r.run.pings, max_range_m, r.objects, spec.score);
  std::vector<study::ScoredCandidate> candidates;
  for (const atr::CandidateReport& c : r.run.candidates) {
    const bool survived = c.candidate.fate == atr::CandidateFate::kReported ||
                          c.candidate.fate == atr::CandidateFate::kBelowThreshold;
    candidates.push_back(
        {c.contact.north_m, c.contact.east_m, c.candidate.detection.score, survived});
  }
  r.detector_froc = study::froc_counts(r.score, candidates, spec.froc_thresholds,
                                       spec.onboard.look_radius_m, spec.score.match_radius_m);
  if (spec.model && spec.model->classification_gate) {
    // the detections the detector reported, scored by the classification gate; those the
    // detection gate kept out, or whose chip could not be classified, pass at no threshold
    std::vector<study::ScoredCandidate> gated;
    for (const atr::CandidateReport& c : r.run.candidates) {
      if (c.candidate.fate != atr::CandidateFate::kReported) continue;
      double p = c.p_classification;
      if (std::isnan(p)) p = c.passed ? std::numeric_limits<double>::infinity() : -1.0;
      gated.push_back({c.contact.north_m, c.contact.east_m, p, true});
    }
    r.gate_froc = study::froc_counts(r.score, gated, spec.gate_thresholds,
                                     spec.onboard.look_radius_m, spec.score.match_radius_m);
  }
  return r;
}

}  // namespace sonarloop::mission
