#include "mission/survey_training.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <stdexcept>

#include "mission/layout.h"
#include "sim/scene/scene.h"
#include "study/sweep.h"

namespace sonarloop::mission {
namespace {

// The training scenario of survey i of pass `pass` of scenario j: its targets drawn afresh.
Scenario training_scenario(const TrainingSurveys& t, int pass, std::size_t j, int i,
                           std::uint64_t* seed_out) {
  const std::uint64_t seed = t.first_seed + 100000 * static_cast<std::uint64_t>(pass - 1) +
                             1000 * j + static_cast<std::uint64_t>(i);
  const AgentSetup setup0 = make_agent_setup(t.scenarios[j], t.agent);
  Scenario sc = random_layout(t.scenarios[j], seed, repeat_types(t.types, t.per_type), setup0.area,
                              t.min_separation_m);
  sc.scene.seed = seed;
  *seed_out = seed;
  return sc;
}

// Labels a detection at (north, east) of survey `seed` into `rows`: 1 and the target's id when
// it is one of the scene's targets, else 0 and -1.
void add_label(GateRows& rows, const scene::Scene& scene, std::uint64_t seed, int scenario,
               double north_m, double east_m, double radius_m) {
  rows.scenario.push_back(scenario);
  const auto& targets = scene.desc().targets;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const Vec2& p = targets[i].position_m;
    if (std::hypot(p.x() - north_m, p.y() - east_m) <= radius_m) {
      rows.y.push_back(1);
      rows.target.push_back(static_cast<std::int64_t>(seed * 1000 + i));
      return;
    }
  }
  rows.y.push_back(0);
  rows.target.push_back(-1);
}

// Flies every survey of one pass; `on_candidate` sees each candidate with its scene.
void fly_pass(
    const TrainingSurveys& t, int pass, const std::optional<atr::Model>& model,
    const std::function<void(const scene::Scene&, std::uint64_t seed, int scenario,
                             const atr::Waterfall&, const atr::CandidateReport&)>& on_candidate,
    const std::function<void(int done, int total)>& after_survey, const StopFn& stop) {
  const int total = static_cast<int>(t.scenarios.size()) * t.surveys_per_scenario;
  int done = 0;
  atr::OnboardOptions onboard = t.onboard;
  onboard.detector.min_pings = t.detector_rules.min_pings;
  onboard.detector.min_along_m = t.detector_rules.min_along_m;
  for (std::size_t j = 0; j < t.scenarios.size(); ++j) {
    for (int i = 0; i < t.surveys_per_scenario; ++i) {
      if (stop && stop()) return;
      std::uint64_t seed = 0;
      const Scenario sc = training_scenario(t, pass, j, i, &seed);
      const scene::Scene scene(sc.scene);
      AgentOverrides survey_only = t.agent;
      survey_only.relooks = false;
      const AgentSetup setup = make_agent_setup(sc, survey_only);
      autonomy::Agent agent(setup.params, setup.survey, setup.start);
      LockstepHooks hooks;
      hooks.stop_requested = stop;
      hooks.on_candidate = [&](const atr::Waterfall& w, const atr::CandidateReport& r) {
        on_candidate(scene, seed, static_cast<int>(j), w, r);
      };
      (void)run_lockstep(sc, scene, model, onboard, agent, t.lockstep, hooks);
      after_survey(++done, total);
    }
  }
}

// A gate fitted on `rows`, or an error that says what the training surveys lacked.
atr::LogisticGate fit_or_explain(atr::GateStage stage, const GateRows& rows,
                                 const atr::GateFitOptions& o) {
  try {
    return atr::fit_gate(stage, rows.x, rows.y, o, rows.target);
  } catch (const std::invalid_argument& e) {
    std::size_t targets = 0;
    for (const int y : rows.y)
      targets += static_cast<std::size_t>(y);
    throw std::runtime_error(std::string("the ") + atr::gate_stage_name(stage) +
                             " gate cannot be fitted on " + std::to_string(targets) +
                             " target and " + std::to_string(rows.y.size() - targets) +
                             " clutter detections of the training surveys (" + e.what() +
                             "): fly more or larger surveys (more surveys per scenario, more "
                             "targets per type, a larger area)");
  }
}

}  // namespace

std::map<std::string, atr::ClassMetadata, std::less<>> survey_class_metadata() {
  auto out = study::target_class_metadata();
  out[std::string(atr::kClutterClassName)] = {false, std::nullopt, true};
  return out;
}

TrainingData collect_training_data(const TrainingSurveys& t, const TrainingProgressFn& progress,
                                   const StopFn& stop) {
  TrainingData data;
  TrainingProgress p;
  p.pass = 1;
  std::unique_ptr<SurveyChipCollector> collector;
  const scene::Scene* current = nullptr;
  const auto flush = [&] {
    if (!collector) return;
    const SurveyChipCounts& n = collector->counts();
    p.counts.targets += n.targets;
    p.counts.clutter += n.clutter;
    p.counts.rock_centred += n.rock_centred;
    p.counts.skipped += n.skipped;
    p.counts.clutter_seen += n.clutter_seen;
    for (atr::LabelledChip& c : collector->chips())
      data.chips.push_back(std::move(c));
    collector.reset();
  };
  fly_pass(
      t, 1, std::nullopt,
      [&](const scene::Scene& scene, std::uint64_t seed, int scenario, const atr::Waterfall& w,
          const atr::CandidateReport& r) {
        if (&scene != current) {
          flush();
          collector = std::make_unique<SurveyChipCollector>(scene, t.chips, seed,
                                                            "survey " + std::to_string(seed));
          current = &scene;
        }
        collector->on_candidate(w, r);
        if (r.candidate.fate != atr::CandidateFate::kReported) return;
        data.detection.x.push_back(atr::detection_features(r.candidate.detection));
        add_label(data.detection, scene, seed, scenario, r.contact.north_m, r.contact.east_m,
                  t.label_radius_m);
      },
      [&](int done, int total) {
        flush();
        current = nullptr;
        p.survey = done;
        p.surveys = total;
        p.rows = data.detection.y.size();
        if (progress) progress(p);
      },
      stop);
  flush();
  return data;
}

GateRows collect_classification_rows(const TrainingSurveys& t, const atr::Model& model,
                                     const TrainingProgressFn& progress, const StopFn& stop) {
  GateRows rows;
  atr::Model m = model;
  m.classification_gate.reset();
  TrainingProgress p;
  p.pass = 2;
  fly_pass(
      t, 2, m,
      [&](const scene::Scene& scene, std::uint64_t seed, int scenario, const atr::Waterfall&,
          const atr::CandidateReport& r) {
        // every detection classified (identified as clutter too): what the gate will judge
        if (r.candidate.fate != atr::CandidateFate::kReported) return;
        if (r.gate_features.size() != atr::gate_feature_count(atr::GateStage::kClassification))
          return;
        rows.x.push_back(r.gate_features);
        add_label(rows, scene, seed, scenario, r.contact.north_m, r.contact.east_m,
                  t.label_radius_m);
      },
      [&](int done, int total) {
        p.survey = done;
        p.surveys = total;
        p.rows = rows.y.size();
        if (progress) progress(p);
      },
      stop);
  return rows;
}

GateChoice choose_gate_threshold(const atr::LogisticGate& gate, const GateRows& rows,
                                 const std::vector<std::string>& scenario_names,
                                 int targets_per_scenario, double keep_targets,
                                 double max_false_per_target, GateAim aim) {
  const std::size_t n = scenario_names.size();
  // per row: its probability; per target: its best
  std::vector<double> p(rows.x.size());
  for (std::size_t r = 0; r < rows.x.size(); ++r)
    p[r] = gate.probability(rows.x[r]);
  std::vector<std::map<std::int64_t, double>> best(n);
  std::vector<std::vector<double>> clutter(n);
  for (std::size_t r = 0; r < rows.x.size(); ++r) {
    const auto j = static_cast<std::size_t>(rows.scenario[r]);
    if (j >= n) continue;
    if (rows.y[r] == 1) {
      auto [it, added] = best[j].try_emplace(rows.target[r], p[r]);
      if (!added) it->second = std::max(it->second, p[r]);
    } else {
      clutter[j].push_back(p[r]);
    }
  }
  // the largest threshold keeping `keep` of the targets whose best are `b` (the targets that
  // reach the gate: one the detector never reported is not the gate's to keep); 0 without any
  const auto own = [&](const std::map<std::int64_t, double>& b) {
    std::vector<double> v;
    for (const auto& [id, q] : b)
      v.push_back(q);
    std::sort(v.begin(), v.end(), std::greater<>());
    const auto need =
        static_cast<std::size_t>(std::ceil(keep_targets * static_cast<double>(v.size()) - 1e-9));
    if (v.empty()) return 0.0;
    return v[std::clamp<std::size_t>(need, 1, v.size()) - 1];
  };
  const auto count_at = [](const std::vector<double>& v, double t) {
    return static_cast<int>(std::count_if(v.begin(), v.end(), [t](double q) { return q >= t; }));
  };
  // the smallest threshold passing at most `allowed` of the clutter probabilities `v`
  const auto budget = [](std::vector<double> v, double allowed) {
    const auto m = static_cast<std::size_t>(std::max(0.0, std::floor(allowed + 1e-9)));
    if (v.size() <= m) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(m), v.end(),
                     std::greater<>());
    // passes q >= threshold: the (m + 1)-th largest fails (none can when it is 1: then 1)
    return std::min(1.0, std::nextafter(v[m], 2.0));
  };
  GateChoice c;
  c.threshold = 1.0;
  bool any = false;
  double ask = 0.0;  // kFalseBudget: the highest ask
  for (std::size_t j = 0; j < n; ++j) {
    GateScenario s;
    s.name = scenario_names[j];
    s.targets = targets_per_scenario;
    s.own_threshold = own(best[j]);
    s.reaching = static_cast<int>(best[j].size());
    const double allowed = max_false_per_target * targets_per_scenario;
    s.budget_threshold = budget(clutter[j], allowed);
    const int fa = count_at(clutter[j], s.own_threshold);
    s.served = targets_per_scenario > 0 && s.own_threshold > 0.0 && fa <= allowed;
    if (s.served) {
      c.threshold = std::min(c.threshold, s.own_threshold);
      any = true;
    }
    ask = std::max(ask, std::min(s.budget_threshold, s.own_threshold));
    c.scenarios.push_back(s);
  }
  if (any && aim == GateAim::kFalseBudget) c.threshold = std::min(c.threshold, ask);
  if (!any) {
    // none served: keep_targets of all the targets
    std::map<std::int64_t, double> all;
    for (const auto& b : best)
      all.insert(b.begin(), b.end());
    c.threshold = own(all);
  }
  for (std::size_t j = 0; j < n; ++j) {
    GateScenario& s = c.scenarios[j];
    int kept = 0;
    for (const auto& [id, q] : best[j])
      kept += q >= c.threshold;
    s.kept = s.reaching > 0 ? static_cast<double>(kept) / s.reaching : 0.0;
    s.false_per_target =
        targets_per_scenario > 0
            ? static_cast<double>(count_at(clutter[j], c.threshold)) / targets_per_scenario
            : 0.0;
  }
  return c;
}

atr::Model train_survey_model(const TrainingSurveys& t, const SurveyModelOptions& o,
                              const TrainingProgressFn& progress, const StopFn& stop) {
  std::vector<std::string> names;
  for (const Scenario& s : t.scenarios)
    names.push_back(s.scene.name);
  const int targets_per_scenario =
      t.surveys_per_scenario * t.per_type * static_cast<int>(t.types.size());
  // a gate's threshold chosen to serve the seabeds it can (choose_gate_threshold)
  const auto choose = [&](atr::GateStage stage, atr::LogisticGate& g, const GateRows& rows,
                          const atr::GateFitOptions& f, double max_false) {
    const GateChoice c = choose_gate_threshold(
        g, rows, names, targets_per_scenario, f.keep_targets, max_false,
        stage == atr::GateStage::kDetection ? GateAim::kKeepTargets : GateAim::kFalseBudget);
    g.threshold = c.threshold;
    if (o.on_gate_choice) o.on_gate_choice(stage, c);
  };
  TrainingData data = collect_training_data(t, progress, stop);
  if (stop && stop()) throw std::runtime_error("training stopped (pass 1 of 2)");
  atr::TrainOptions train = o.train;
  if (train.class_metadata.empty()) train.class_metadata = survey_class_metadata();
  // a chip cut where the waterfall holds no echo (its centre in the nadir gap or beyond the
  // range, all 0 once cropped) cannot be normalised: left out, as the onboard classifier
  // leaves such a chip unclassified
  train.skip_degenerate = true;
  atr::TrainReport skipped;
  atr::Model model = atr::train_model(data.chips, train, &skipped);
  if (o.on_skipped_chips) o.on_skipped_chips(skipped.skipped);
  model.detector_rules = t.detector_rules;
  if (o.on_gate_rows) o.on_gate_rows(atr::GateStage::kDetection, data.detection);
  model.detection_gate =
      fit_or_explain(atr::GateStage::kDetection, data.detection, o.detection_gate);
  choose(atr::GateStage::kDetection, *model.detection_gate, data.detection, o.detection_gate,
         o.detection_max_false_per_target);
  data = TrainingData{};  // the chips' memory back before pass 2
  const GateRows rows = collect_classification_rows(t, model, progress, stop);
  if (stop && stop()) throw std::runtime_error("training stopped (pass 2 of 2)");
  if (o.on_gate_rows) o.on_gate_rows(atr::GateStage::kClassification, rows);
  model.classification_gate =
      fit_or_explain(atr::GateStage::kClassification, rows, o.classification_gate);
  choose(atr::GateStage::kClassification, *model.classification_gate, rows, o.classification_gate,
         o.classification_max_false_per_target);
  atr::validate_model(model);
  return model;
}

std::string gate_rows_csv(atr::GateStage stage, const GateRows& rows) {
  std::string out;
  for (const char* name : atr::gate_feature_names(stage))
    out += std::string(name) + ",";
  out += "label,target,scenario\n";
  char v[64];
  for (std::size_t r = 0; r < rows.x.size(); ++r) {
    for (const double x : rows.x[r]) {
      std::snprintf(v, sizeof v, "%.9g,", x);
      out += v;
    }
    std::snprintf(v, sizeof v, "%d,%lld,%d\n", rows.y[r], static_cast<long long>(rows.target[r]),
                  rows.scenario[r]);
    out += v;
  }
  return out;
}

}  // namespace sonarloop::mission
