#include "mission/survey_training.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "mission/layout.h"
#include "sim/scene/scene.h"

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
void add_label(GateRows& rows, const scene::Scene& scene, std::uint64_t seed, double north_m,
               double east_m, double radius_m) {
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
    const std::function<void(const scene::Scene&, std::uint64_t seed, const atr::Waterfall&,
                             const atr::CandidateReport&)>& on_candidate,
    const std::function<void(int done, int total)>& after_survey, const StopFn& stop) {
  const int total = static_cast<int>(t.scenarios.size()) * t.surveys_per_scenario;
  int done = 0;
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
        on_candidate(scene, seed, w, r);
      };
      (void)run_lockstep(sc, scene, model, t.onboard, agent, t.lockstep, hooks);
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
  std::map<std::string, atr::ClassMetadata, std::less<>> out;
  for (const auto& t : targets::target_type_table())
    out[std::string(t.key)] = {t.mine_like, t.size_m.z()};
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
      [&](const scene::Scene& scene, std::uint64_t seed, const atr::Waterfall& w,
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
        add_label(data.detection, scene, seed, r.contact.north_m, r.contact.east_m,
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
      [&](const scene::Scene& scene, std::uint64_t seed, const atr::Waterfall&,
          const atr::CandidateReport& r) {
        // every detection classified (identified as clutter too): what the gate will judge
        if (r.candidate.fate != atr::CandidateFate::kReported) return;
        if (r.gate_features.size() != atr::gate_feature_count(atr::GateStage::kClassification))
          return;
        rows.x.push_back(r.gate_features);
        add_label(rows, scene, seed, r.contact.north_m, r.contact.east_m, t.label_radius_m);
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

atr::Model train_survey_model(const TrainingSurveys& t, const SurveyModelOptions& o,
                              const TrainingProgressFn& progress, const StopFn& stop) {
  TrainingData data = collect_training_data(t, progress, stop);
  if (stop && stop()) throw std::runtime_error("training stopped (pass 1 of 2)");
  atr::TrainOptions train = o.train;
  if (train.class_metadata.empty()) train.class_metadata = survey_class_metadata();
  atr::Model model = atr::train_model(data.chips, train);
  if (o.on_gate_rows) o.on_gate_rows(atr::GateStage::kDetection, data.detection);
  model.detection_gate =
      fit_or_explain(atr::GateStage::kDetection, data.detection, o.detection_gate);
  data = TrainingData{};  // the chips' memory back before pass 2
  const GateRows rows = collect_classification_rows(t, model, progress, stop);
  if (stop && stop()) throw std::runtime_error("training stopped (pass 2 of 2)");
  if (o.on_gate_rows) o.on_gate_rows(atr::GateStage::kClassification, rows);
  model.classification_gate =
      fit_or_explain(atr::GateStage::kClassification, rows, o.classification_gate);
  atr::validate_model(model);
  return model;
}

std::string gate_rows_csv(atr::GateStage stage, const GateRows& rows) {
  std::string out;
  for (const char* name : atr::gate_feature_names(stage))
    out += std::string(name) + ",";
  out += "label,target\n";
  char v[64];
  for (std::size_t r = 0; r < rows.x.size(); ++r) {
    for (const double x : rows.x[r]) {
      std::snprintf(v, sizeof v, "%.9g,", x);
      out += v;
    }
    std::snprintf(v, sizeof v, "%d,%lld\n", rows.y[r], static_cast<long long>(rows.target[r]));
    out += v;
  }
  return out;
}

}  // namespace sonarloop::mission
