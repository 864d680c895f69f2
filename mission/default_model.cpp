#include "mission/default_model.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include "atr/model_file.h"
#include "config/default_scenario.h"
#include "config/loader/scenario_loader.h"

namespace sonarloop::mission {
namespace fs = std::filesystem;
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Bumped whenever the recipe or what it depends on (detector, chips, gates) changes in a way the
// key below does not see.
constexpr const char* kRecipeVersion = "survey-recipe-3";
constexpr const char* kTrainingScenarios[] = {"survey_flat", "survey_ripples", "survey_clutter",
                                              "survey_rocky", "mission_20"};

const std::string& builtin_yaml(const std::string& name) {
  for (const auto& [n, yaml] : config::builtin_scenarios())
    if (n == name) return yaml;
  throw std::runtime_error("default model: no built-in scenario '" + name + "'");
}

// FNV-1a, 64 bits (Fowler, Noll, Vo): a stable hash of the recipe's text.
std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 0xCBF29CE484222325ULL;
  for (const unsigned char c : text) {
    h ^= c;
    h *= 0x100000001B3ULL;
  }
  return h;
}

std::string cache_dir() {
  if (const char* d = std::getenv("SONARLOOP_CACHE_DIR"); d && *d) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return std::string(d) + "/sonarloop";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/sonarloop";
  return ".sonarloop-cache";
}

}  // namespace

TrainingSurveys default_training_surveys() {
  TrainingSurveys t;
  for (const char* name : kTrainingScenarios)
    t.scenarios.push_back(config::parse_scenario(builtin_yaml(name), std::string(name) + ".yaml"));
  t.types = {targets::TargetType::kManta,      targets::TargetType::kRockan,
             targets::TargetType::kCylinder,   targets::TargetType::kLargeCuboid,
             targets::TargetType::kHemisphere, targets::TargetType::kSmallHemisphere,
             targets::TargetType::kBox};
  t.lockstep.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  t.agent.relooks = false;
  return t;
}

SurveyModelOptions default_model_options() {
  SurveyModelOptions o;
  o.train.p = 10;
  o.train.aspect_sectors = 8;
  // the chip's central 1.2 m (of 3 m) read twice, the highlight and the shadow, and the two
  // readings fused (atr/subspace_classifier.h, "Fused readings"; docs/autonomy.md, "Highlight
  // and shadow fused")
  o.train.preprocess.crop_fraction = 0.4;
  o.train.preprocess.levels = atr::ChipLevels::kAboveSeabed;
  atr::ChipPreprocess shadow = o.train.preprocess;
  shadow.levels = atr::ChipLevels::kBelowSeabed;
  o.train.views = {shadow};
  return o;
}

std::string default_model_path() {
  const TrainingSurveys t = default_training_surveys();
  const SurveyModelOptions o = default_model_options();
  std::string key = std::string(kRecipeVersion) + "\n" + SONARLOOP_VERSION + "\n";
  char line[256];
  std::snprintf(line, sizeof line, "%llu %d %d %.6g %d %d %d %.6g %.6g %.6g %d %.6g\n",
                static_cast<unsigned long long>(t.first_seed), t.surveys_per_scenario, t.per_type,
                t.min_separation_m, t.chips.max_clutter, o.train.p, o.train.aspect_sectors,
                o.detection_gate.keep_targets, o.classification_gate.keep_targets,
                t.onboard.detector.min_height_m, t.detector_rules.min_pings,
                t.detector_rules.min_along_m);
  key += line;
  key += atr::preprocess_label(o.train.preprocess);
  for (const atr::ChipPreprocess& v : o.train.views)
    key += " + " + atr::preprocess_label(v);
  key += "\n";
  for (const char* name : kTrainingScenarios)
    key += builtin_yaml(name);
  char file[64];
  std::snprintf(file, sizeof file, "default-%016llx.slpca",
                static_cast<unsigned long long>(fnv1a(key)));
  return (fs::path(cache_dir()) / "models" / file).string();
}

bool is_default_model(const std::string& spec) {
  return spec == "default";
}

std::string ensure_default_model(bool quiet, const StopFn& stop) {
  const std::string path = default_model_path();
  if (fs::exists(path)) return path;
  const fs::path dir = fs::path(path).parent_path();
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    throw std::runtime_error("default model: cannot create the cache folder " + dir.string() +
                             ": " + ec.message() + " (set SONARLOOP_CACHE_DIR)");
  }
  std::fprintf(stderr,
               "default model: not cached yet: training it once from the documented recipe "
               "(docs/autonomy.md; about 6 minutes on 2 cores) into %s\n",
               path.c_str());
  const auto t0 = std::chrono::steady_clock::now();
  const atr::Model model = train_survey_model(
      default_training_surveys(), default_model_options(),
      [&](const TrainingProgress& p) {
        if (quiet) return;
        std::fprintf(stderr, "default model: pass %d of 2, survey %d of %d done (%.0f s)\n", p.pass,
                     p.survey, p.surveys, seconds_since(t0));
      },
      stop);
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  atr::save_model(model, tmp);
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp);
    throw std::runtime_error("default model: cannot move it into place at " + path + ": " +
                             ec.message());
  }
  std::fprintf(stderr, "default model: trained in %.0f s: %s\n", seconds_since(t0), path.c_str());
  return path;
}

}  // namespace sonarloop::mission
