#include "tools/cmd_mission_lockstep.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "autonomy/autonomy_io.h"
#include "drivers/json/json_writer.h"
#include "mission/mission_report.h"
#include "mission/mission_run.h"
#include "tools/chip_options.h"
#include "tools/cli_helpers.h"
#include "tools/output_file.h"
#include "tools/progress.h"

namespace sonarloop::tools {
using autonomy::agent_report_json;
using autonomy::AgentRunInfo;
namespace {

std::vector<std::uint64_t> seed_list(const Args& args, const config::Scenario& scenario) {
  const auto first = args.get_int("--seed", 0, (1LL << 53));
  const auto n = args.get_int("--seeds", 1, 100000).value_or(1);
  const std::uint64_t s0 = first ? static_cast<std::uint64_t>(*first) : scenario.scene.seed;
  std::vector<std::uint64_t> seeds;
  for (long long i = 0; i < n; ++i)
    seeds.push_back(s0 + static_cast<std::uint64_t>(i));
  return seeds;
}

// Writes `text` to DIR/NAME (whole-file write, the error names the file).
void write_text(const std::filesystem::path& dir, const std::string& name,
                const std::string& text) {
  OutputFile f("--out", (dir / name).string());
  f.write_and_close(text);
}

}  // namespace

int run_lockstep_missions(const Args& args, const std::string& model_path,
                          const config::Scenario& scenario) {
  mission::MissionSpec spec;
  spec.scenario = scenario;
  spec.model = load_model_if(model_path);
  set_gate_threshold(spec.model, args.get_double("--gate-threshold", 0.0, 1.0));
  spec.agent = agent_options(args);
  const std::string layout = args.get_or("--layout", "scenario");
  if (layout != "scenario" && layout != "random") {
    throw UsageError("--layout: expected scenario or random, got '" + layout + "'");
  }
  spec.random_layout = layout == "random";
  spec.onboard.classify_candidates = args.has("--classify-candidates");
  if (const auto h = args.get_double("--detector-threshold", 0.0, 5.0)) {
    spec.onboard.detector.min_height_m = *h;
    spec.onboard.detector.candidate_min_height_m =
        std::min(spec.onboard.detector.candidate_min_height_m, *h);
  }
  spec.lockstep.threads =
      static_cast<int>(args.get_int("--threads", 1, 256)
                           .value_or(std::max(1u, std::thread::hardware_concurrency())));
  if (const auto d = args.get_double("--max-duration", 1.0, 1e7)) spec.lockstep.max_duration_s = *d;
  spec.score.match_radius_m =
      args.get_double("--match-radius", 0.01, 100.0).value_or(spec.score.match_radius_m);
  const std::optional<double> rate = args.get("--rate") && *args.get("--rate") != "max"
                                         ? args.get_double("--rate", 0.01, 1000.0)
                                         : std::nullopt;
  const std::vector<std::uint64_t> seeds = seed_list(args, scenario);
  const std::string report_path = args.get_or("--report", "out/mission.json");
  const std::filesystem::path out_dir =
      args.get_or("--out", (std::filesystem::path(report_path).parent_path() / "mission").string());
  make_folder("--report", std::filesystem::path(report_path).parent_path());
  make_folder("--out", out_dir);
  OutputFile report("--report", report_path);  // opened now: fails before the run
  const bool quiet = args.has("--quiet");
  try {
    spec.lockstep.validate();
    (void)mission::make_agent_setup(scenario, spec.agent);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  install_stop_flag();
  char pacing[64] = "";
  if (rate) std::snprintf(pacing, sizeof pacing, ", paced at %g x real time", *rate);
  std::fprintf(stderr,
               "mission: scenario '%s' in lock-step, %zu seed%s from %llu, re-looks %s, %d render "
               "thread%s%s; files in %s\n",
               scenario.scene.name.c_str(), seeds.size(), seeds.size() == 1 ? "" : "s",
               static_cast<unsigned long long>(seeds.front()), spec.agent.relooks ? "on" : "off",
               spec.lockstep.threads, spec.lockstep.threads == 1 ? "" : "s", pacing,
               out_dir.string().c_str());

  study::SurveyTally tally;
  std::vector<study::FrocCounts> froc, gate_froc;
  std::vector<std::pair<std::uint64_t, study::SurveyScore>> scores;
  std::string missions_json;
  mission::MissionSummary pooled;  // every seed's, added up (mission_done: all of them)
  pooled.mission_done = true;
  bool stopped = false;
  const auto wall0 = std::chrono::steady_clock::now();
  for (const std::uint64_t seed : seeds) {
    const auto seed_wall0 = std::chrono::steady_clock::now();
    std::string events;
    std::string contacts;
    mission::LockstepHooks hooks;
    hooks.stop_requested = [] { return stop_requested(); };
    const double plan_m =
        autonomy::plan_length_m(mission::make_agent_setup(spec.scenario, spec.agent).survey);
    auto next_progress = seed_wall0 + std::chrono::seconds(10);
    hooks.on_batch = [&](const autonomy::Agent& agent) {
      for (const std::string& e : const_cast<autonomy::Agent&>(agent).take_events()) {
        char line[64];
        std::snprintf(line, sizeof line, "t=%.1f s: ", agent.state().t_s);
        events += line + e + "\n";
      }
      // pacing: mission time no faster than --rate x the wall clock
      if (rate) {
        const auto due =
            seed_wall0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                             std::chrono::duration<double>(agent.state().t_s / *rate));
        std::this_thread::sleep_until(due);
      }
      if (!quiet && std::chrono::steady_clock::now() >= next_progress) {
        next_progress += std::chrono::seconds(10);
        std::fprintf(stderr,
                     "mission: seed %llu: %.0f s of mission, %.0f m flown (survey plan %.0f m) "
                     "...\n",
                     static_cast<unsigned long long>(seed), agent.state().t_s, agent.travelled_m(),
                     plan_m);
      }
    };
    hooks.on_contact = [&](const atr::Contact& c) { contacts += atr::contact_json(c) + "\n"; };
    mission::SeedRun r = mission::run_seed(spec, seed, hooks);
    stopped = r.run.stopped;
    const double seed_wall_s = seconds_since(seed_wall0);
    // the agent's report and the mission's (as --realtime), with the survey score
    AgentRunInfo info;
    info.lockstep = true;
    info.threshold = r.setup.params.margin_threshold;
    info.relooks = r.setup.params.relooks;
    info.survey_plan_m = autonomy::plan_length_m(r.setup.survey);
    info.stopped = r.run.stopped;
    info.contacts_received = r.run.contacts.size();
    const std::string agent_report = agent_report_json(*r.agent, info);
    mission::MissionSummary summary;
    const std::string mission_json =
        mission::mission_report_json(agent_report, r.scenario,
                                     "\"seed\": " + std::to_string(seed) +
                                         ",\n  \"survey\": " + mission::survey_score_json(r.score),
                                     &summary, spec.score.match_radius_m);
    missions_json += (missions_json.empty() ? "" : ",\n") + mission_json;
    pooled = mission::add_summaries(pooled, summary);
    tally.add(r.score);
    study::add_froc(froc, r.detector_froc);
    if (!r.gate_froc.empty()) study::add_froc(gate_froc, r.gate_froc);
    scores.emplace_back(seed, r.score);
    const std::string stem = "seed_" + std::to_string(seed);
    write_text(out_dir, stem + "_contacts.jsonl", contacts);
    write_text(out_dir, stem + "_agent.log", events);
    write_text(out_dir, stem + "_candidates.csv", mission::candidates_csv(r.run.candidates));
    if (!quiet) {
      std::fprintf(stderr,
                   "mission: seed %llu: %zu pings, %zu contacts (%llu detections identified as "
                   "clutter), %.0f s of mission in %.1f s wall (%.0f x real time; classifying "
                   "%.1f s)\n",
                   static_cast<unsigned long long>(seed), r.run.pings.size(), r.run.contacts.size(),
                   static_cast<unsigned long long>(r.run.onboard.clutter), r.run.mission_s,
                   seed_wall_s, r.run.mission_s / std::max(seed_wall_s, 1e-9),
                   r.run.onboard.classify_total_s);
      mission::print_mission_summary(summary);
    }
    if (stopped) break;
  }
  const std::vector<study::SurveyRow> rows = study::survey_rows(tally);
  write_text(out_dir, "survey.csv", study::survey_rows_csv(rows));
  write_text(out_dir, "survey_targets.csv", mission::survey_targets_csv(scores));
  write_text(out_dir, "survey_false_contacts.csv", mission::survey_false_contacts_csv(scores));
  write_text(out_dir, "detector_froc.csv", study::froc_csv(froc));
  if (!gate_froc.empty()) write_text(out_dir, "gate_froc.csv", study::froc_csv(gate_froc));
  json::Writer settings;
  settings.begin_object();
  settings.field("mode", "lockstep").field("scenario", scenario.scene.name);
  settings.field("relooks", spec.agent.relooks).field("relook_all", spec.agent.relook_all);
  settings.field("model", model_path).field("stopped", stopped);
  settings.field("match_radius_m", spec.score.match_radius_m, 6);
  settings.field("layout", layout);
  // the classification gate's operating point in effect (--gate-threshold or the model's)
  if (spec.model && spec.model->classification_gate) {
    settings.field("gate_threshold", spec.model->classification_gate->threshold, 6);
  }
  settings.end_object();
  std::string text = "{\n  \"run\": " + settings.str() +
                     ",\n  \"summary\": " + mission::mission_summary_json(pooled) +
                     ",\n  \"survey\": " + mission::survey_rows_json(rows) +
                     ",\n  \"missions\": [\n" + missions_json + "]\n}\n";
  report.write_and_close(text);
  mission::print_survey_rows(rows);
  std::fprintf(stderr, "mission: %zu mission%s in %.1f s wall; report %s, tables in %s\n",
               scores.size(), scores.size() == 1 ? "" : "s", seconds_since(wall0),
               report_path.c_str(), out_dir.string().c_str());
  return stopped ? 1 : 0;
}

}  // namespace sonarloop::tools
