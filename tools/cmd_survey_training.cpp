#include "tools/cmd_survey_training.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <thread>

#include "atr/model_file.h"
#include "drivers/image/png.h"
#include "mission/default_model.h"
#include "mission/survey_training.h"
#include "sim/targets/target_type.h"
#include "tools/args.h"
#include "tools/cli_helpers.h"
#include "tools/output_file.h"
#include "tools/progress.h"
#include "tools/scenario_source.h"

namespace sonarloop::tools {
namespace fs = std::filesystem;

void write_chip_folder(const std::string& dir, const std::vector<atr::LabelledChip>& chips) {
  const fs::path root(dir);
  if (fs::exists(root) && !fs::is_empty(root)) {
    throw std::runtime_error("--out " + dir + ": the folder is not empty");
  }
  fs::create_directories(root);
  std::map<std::string, int> index;
  std::string csv = "file,class,aspect_deg,mine_like,source\n";
  std::vector<std::uint8_t> grey;
  for (const atr::LabelledChip& c : chips) {
    const std::string name = c.label;
    fs::create_directories(root / name);
    char file[64];
    std::snprintf(file, sizeof file, "%06d.png", index[name]++);
    grey.resize(c.chip.pixels.size());
    for (std::size_t i = 0; i < grey.size(); ++i)
      grey[i] = static_cast<std::uint8_t>(std::clamp(std::lround(c.chip.pixels[i]), 0L, 255L));
    image::write_png_gray8((root / name / file).string(), c.chip.width, c.chip.height, grey);
    const auto type = targets::find_target_type(name);
    const bool mine_like = type && targets::target_type_info(*type).mine_like;
    char line[256];
    std::snprintf(line, sizeof line, "%s/%s,%s,%.3f,%d,%s\n", name.c_str(), file, name.c_str(),
                  c.aspect_deg.value_or(0.0), mine_like ? 1 : 0, c.source.c_str());
    csv += line;
  }
  OutputFile labels("--out", (root / "labels.csv").string());
  labels.write_and_close(csv);
  // the mark of the simulator's chips: `train` then takes the target types' metadata
  OutputFile made("--out", (root / "dataset.json").string());
  made.write_and_close(
      "{\"made_by\": \"sonarloop dataset --surveys\", \"classes\": \"the simulator's target "
      "types and clutter\"}\n");
}

mission::TrainingSurveys training_surveys_of(const Args& args) {
  mission::TrainingSurveys t;
  for (const std::string& path : split_comma_list(args.get_or("--surveys", ""))) {
    t.scenarios.push_back(load_scenario_or_default(path));
  }
  if (t.scenarios.empty()) throw UsageError("--surveys: no scenario given");
  t.surveys_per_scenario = static_cast<int>(
      args.get_int("--surveys-per-scenario", 1, 1000).value_or(t.surveys_per_scenario));
  t.per_type = static_cast<int>(args.get_int("--per-type", 1, 1000).value_or(t.per_type));
  const std::string classes = args.get_or(
      "--classes", "manta,rockan,cylinder,large_cuboid,hemisphere,small_hemisphere,box");
  for (const std::string& key : split_comma_list(classes)) {
    const auto type = targets::find_target_type(key);
    if (!type) {
      throw UsageError("--classes: unknown target type '" + key +
                       "' (allowed: " + targets::target_type_keys_list() + ")");
    }
    t.types.push_back(*type);
  }
  t.first_seed = static_cast<std::uint64_t>(
      args.get_int("--seed", 0, 1LL << 53).value_or(static_cast<long long>(t.first_seed)));
  t.lockstep.threads =
      static_cast<int>(args.get_int("--threads", 1, 256)
                           .value_or(std::max(1u, std::thread::hardware_concurrency())));
  t.agent.relooks = false;
  t.agent.area_margin_m =
      args.get_double("--area-margin", 0.0, 1e4).value_or(t.agent.area_margin_m);
  t.min_separation_m = args.get_double("--min-separation", 0.0, 1e4).value_or(t.min_separation_m);
  t.chips.max_clutter =
      static_cast<int>(args.get_int("--max-clutter", 0, 1000000).value_or(t.chips.max_clutter));
  return t;
}

namespace {

void print_progress(const mission::TrainingProgress& p, std::chrono::steady_clock::time_point t0) {
  if (p.pass == 1) {
    std::fprintf(stderr,
                 "pass 1: survey %d of %d done after %.0f s: %llu target chips, %llu clutter chips "
                 "(of %llu), %zu detections\n",
                 p.survey, p.surveys, seconds_since(t0),
                 static_cast<unsigned long long>(p.counts.targets),
                 static_cast<unsigned long long>(p.counts.clutter),
                 static_cast<unsigned long long>(p.counts.clutter_seen), p.rows);
  } else {
    std::fprintf(stderr, "pass 2: survey %d of %d done after %.0f s: %zu classified detections\n",
                 p.survey, p.surveys, seconds_since(t0), p.rows);
  }
}

}  // namespace

namespace {

// The options of training_surveys_of() and those given.
std::vector<OptionSpec> survey_options(std::vector<OptionSpec> more) {
  std::vector<OptionSpec> o = {{"--out"},         {"--surveys"},     {"--surveys-per-scenario"},
                               {"--per-type"},    {"--classes"},     {"--seed"},
                               {"--max-clutter"}, {"--area-margin"}, {"--min-separation"},
                               {"--threads"}};
  o.insert(o.end(), more.begin(), more.end());
  return o;
}

}  // namespace

int run_survey_dataset(const std::vector<std::string>& argv) {
  const Args args(argv, survey_options({{"--no-clutter", false}}));
  if (!args.positionals().empty()) {
    throw UsageError("unexpected argument '" + args.positionals()[0] + "'");
  }
  const auto out = args.get("--out");
  if (!out) throw UsageError("--out DIR is required");
  if (fs::exists(*out) && !fs::is_empty(*out)) {
    throw UsageError("--out " + *out + ": the folder is not empty");
  }
  mission::TrainingSurveys t = training_surveys_of(args);
  t.chips.clutter = !args.has("--no-clutter");
  install_stop_flag();
  const auto t0 = std::chrono::steady_clock::now();
  std::fprintf(stderr,
               "dataset: chips from %d survey%s of %zu scenario%s (%d of each of %zu types per "
               "survey, random layouts from seed %llu) ...\n",
               t.surveys_per_scenario * static_cast<int>(t.scenarios.size()),
               t.surveys_per_scenario * t.scenarios.size() == 1 ? "" : "s", t.scenarios.size(),
               t.scenarios.size() == 1 ? "" : "s", t.per_type, t.types.size(),
               static_cast<unsigned long long>(t.first_seed));
  const mission::TrainingData data = mission::collect_training_data(
      t, [&](const mission::TrainingProgress& p) { print_progress(p, t0); },
      [] { return stop_requested(); });
  write_chip_folder(*out, data.chips);
  std::fprintf(stderr, "dataset: wrote %zu chips to %s in %.0f s%s\n", data.chips.size(),
               out->c_str(), seconds_since(t0), stop_requested() ? " (stopped early)" : "");
  return stop_requested() ? 1 : 0;
}

int run_survey_train(const std::vector<std::string>& argv) {
  const Args args(argv, survey_options({{"--p"},
                                        {"--aspect-sectors"},
                                        {"--crop"},
                                        {"--levels"},
                                        {"--fuse-levels"},
                                        {"--keep-targets"},
                                        {"--false-per-target"},
                                        {"--gate-rows"}}));
  if (!args.positionals().empty()) {
    throw UsageError("with --surveys, train takes no CHIPS_DIR ('" + args.positionals()[0] + "')");
  }
  const auto out = args.get("--out");
  if (!out) throw UsageError("--out MODEL is required");
  const mission::TrainingSurveys t = training_surveys_of(args);
  // the default model's recipe, with what the command line changes
  mission::SurveyModelOptions o = mission::default_model_options();
  o.train.p = static_cast<int>(args.get_int("--p", 1, 4096).value_or(o.train.p));
  o.train.aspect_sectors =
      static_cast<int>(args.get_int("--aspect-sectors", 1, 360).value_or(o.train.aspect_sectors));
  {
    std::vector<atr::ChipLevels> fused;
    for (const atr::ChipPreprocess& v : o.train.views)
      fused.push_back(v.levels);
    o.train.preprocess.levels = levels_option(args, o.train.preprocess.levels);
    // --levels alone naming the recipe's other reading: that reading alone
    if (!args.get("--fuse-levels")) std::erase(fused, o.train.preprocess.levels);
    o.train.preprocess.crop_fraction =
        args.get_double("--crop", 0.05, 1.0).value_or(o.train.preprocess.crop_fraction);
    o.train.views = fused_levels_option(args, o.train.preprocess, fused);
  }
  if (const auto keep = args.get_double("--keep-targets", 0.5, 1.0)) {
    o.classification_gate.keep_targets = *keep;
    o.detection_gate.keep_targets = std::max(*keep, o.detection_gate.keep_targets);
  }
  if (const auto budget = args.get_double("--false-per-target", 0.0, 100.0))
    o.classification_max_false_per_target = *budget;
  o.on_gate_choice = [](atr::GateStage s, const mission::GateChoice& c) {
    std::printf("%s gate: threshold %.4g\n", atr::gate_stage_name(s), c.threshold);
    for (const mission::GateScenario& g : c.scenarios) {
      std::printf(
          "  %-18s %s: its targets kept %.1f %%, %.2f false detections per target "
          "(its own threshold %.3g, its budget's %.3g)%s\n",
          g.name.c_str(), g.served ? "served" : "not served", 100.0 * g.kept, g.false_per_target,
          g.own_threshold, g.budget_threshold,
          g.served ? "" : ": keeping its targets would cost too many false detections");
    }
  };
  o.on_skipped_chips = [](const std::vector<atr::SkippedChip>& s) {
    if (!s.empty())
      std::printf("%zu training chips left out (constant: no echo where they were cut)\n",
                  s.size());
  };
  if (const auto prefix = args.get("--gate-rows")) {
    o.on_gate_rows = [prefix](atr::GateStage s, const mission::GateRows& rows) {
      OutputFile f("--gate-rows", *prefix + "_" + atr::gate_stage_name(s) + ".csv");
      f.write_and_close(mission::gate_rows_csv(s, rows));
    };
  }
  // the model's folder made (as `mission` makes its report's); an unwritable place fails now,
  // not after the training, and a model already there is kept until the new one is written
  make_folder("--out", std::filesystem::path(*out).parent_path());
  {
    const std::string probe = *out + ".probe." + std::to_string(::getpid());
    OutputFile check("--out", probe);
    check.write_and_close("");
    std::filesystem::remove(probe);
  }
  install_stop_flag();
  const auto t0 = std::chrono::steady_clock::now();
  std::fprintf(stderr,
               "train: a model from 2 x %d surveys of %zu scenario%s (%d of each of %zu types per "
               "survey, random layouts from seed %llu) ...\n",
               t.surveys_per_scenario * static_cast<int>(t.scenarios.size()), t.scenarios.size(),
               t.scenarios.size() == 1 ? "" : "s", t.per_type, t.types.size(),
               static_cast<unsigned long long>(t.first_seed));
  const atr::Model model = mission::train_survey_model(
      t, o, [&](const mission::TrainingProgress& p) { print_progress(p, t0); },
      [] { return stop_requested(); });
  atr::save_model(model, *out);
  std::printf("trained on surveys in %.0f s: %zu classes", seconds_since(t0), model.classes.size());
  for (const auto& c : model.classes) {
    int chips = 0;
    for (const auto& sub : c.subspaces)
      chips += sub.train_count;
    std::printf("%s %s (%d chips)", &c == &model.classes.front() ? ":" : ",", c.name.c_str(),
                chips);
  }
  std::printf(
      "\ngates: detection threshold %.4f (keeps %.0f %% of the training targets), "
      "classification threshold %.4f (%.2f false detections per target where that keeps %.0f %% "
      "of a seabed's targets)\nwrote %s\n",
      model.detection_gate->threshold, 100 * o.detection_gate.keep_targets,
      model.classification_gate->threshold, o.classification_max_false_per_target,
      100 * o.classification_gate.keep_targets, out->c_str());
  return 0;
}

}  // namespace sonarloop::tools
