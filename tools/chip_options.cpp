#include "tools/chip_options.h"

#include <algorithm>
#include <cstdlib>

#include "atr/model_file.h"
#include "mission/default_model.h"
#include "mission/survey_training.h"
#include "sim/targets/target_type.h"
#include "tools/cli_helpers.h"

namespace sonarloop::tools {
namespace {

constexpr long kMaxChipSide = 8192;

// A class named in an option must be a class of the training set.
void require_class(const std::string& option, const std::string& name,
                   const std::vector<std::string>& classes) {
  if (std::find(classes.begin(), classes.end(), name) != classes.end()) return;
  std::string all;
  for (const auto& c : classes)
    all += (all.empty() ? "" : ", ") + c;
  throw UsageError(option + ": '" + name + "' is not a class of the training set (" + all + ")");
}

// "A=0.5" -> (A, 0.5); UsageError when malformed or out of range.
std::pair<std::string, double> parse_height(const std::string& item) {
  const auto eq = item.find('=');
  const std::string name = eq == std::string::npos ? "" : item.substr(0, eq);
  const std::string value = eq == std::string::npos ? "" : item.substr(eq + 1);
  char* end = nullptr;
  const double h = value.empty() ? -1.0 : std::strtod(value.c_str(), &end);
  if (name.empty() || value.empty() || *end != '\0' || !atr::valid_class_height(h)) {
    throw UsageError("--height: '" + item + "' is not CLASS=METRES with 0 to " +
                     std::to_string(static_cast<int>(atr::kMaxClassHeight_m)) +
                     " m (e.g. manta=0.47)");
  }
  return {name, h};
}

}  // namespace

std::optional<study::ChipSize> chip_size_option(const Args& args) {
  const auto text = args.get("--size");
  if (!text) return std::nullopt;
  const auto x = text->find_first_of("xX");
  char* end_w = nullptr;
  char* end_h = nullptr;
  const std::string w_text = x == std::string::npos ? "" : text->substr(0, x);
  const std::string h_text = x == std::string::npos ? "" : text->substr(x + 1);
  const long w = std::strtol(w_text.c_str(), &end_w, 10);
  const long h = std::strtol(h_text.c_str(), &end_h, 10);
  if (w_text.empty() || h_text.empty() || *end_w != '\0' || *end_h != '\0' || w < 1 || h < 1 ||
      w > kMaxChipSide || h > kMaxChipSide) {
    throw UsageError("--size: '" + *text + "' is not WIDTHxHEIGHT in pixels (e.g. 64x64, 1 to " +
                     std::to_string(kMaxChipSide) + " a side)");
  }
  return study::ChipSize{static_cast<int>(w), static_cast<int>(h)};
}

std::map<std::string, atr::ClassMetadata, std::less<>> sim_class_metadata() {
  // the simulator's target types, and the false alarms of training surveys (`dataset
  // --surveys`): not a target, height unknown
  return mission::survey_class_metadata();
}

std::map<std::string, atr::ClassMetadata, std::less<>> class_metadata_options(
    const Args& args, const std::vector<std::string>& classes, bool simulated) {
  std::map<std::string, atr::ClassMetadata, std::less<>> meta;
  if (simulated) meta = sim_class_metadata();
  std::optional<std::string> mine = args.get("--mine-like");
  if (!mine && args.has("--mine-classes")) mine = args.get("--mine-classes");
  if (mine) {
    const std::vector<std::string> names = split_comma_list(*mine);
    for (const auto& n : names)
      require_class("--mine-like", n, classes);
    for (auto& [name, m] : meta)
      m.mine_like = false;
    for (const auto& n : names)
      meta[n].mine_like = true;
  }
  if (const auto heights = args.get("--height")) {
    for (const auto& item : split_comma_list(*heights)) {
      const auto [name, h] = parse_height(item);
      require_class("--height", name, classes);
      meta[name].height_m = h;
    }
  }
  return meta;
}

void fill_legacy_class_heights(atr::Model& m, std::uint16_t file_version) {
  if (file_version >= 3) return;
  const auto sim = sim_class_metadata();
  for (auto& c : m.classes) {
    if (const auto it = sim.find(c.name); it != sim.end()) c.height_m = it->second.height_m;
  }
}

atr::Model load_model_with_metadata(const std::string& path) {
  std::uint16_t version = 0;
  atr::Model m = atr::load_model(path, &version);
  fill_legacy_class_heights(m, version);
  return m;
}

std::optional<atr::Model> load_model_if(const std::optional<std::string>& path) {
  if (!path) return std::nullopt;
  // "default": the default model, built and cached the first time (mission/default_model.h)
  if (mission::is_default_model(*path))
    return load_model_with_metadata(
        mission::ensure_default_model(false, [] { return stop_requested(); }));
  return load_model_with_metadata(*path);  // older model files: heights of simulated types
}

void set_gate_threshold(std::optional<atr::Model>& model, std::optional<double> threshold) {
  if (!threshold) return;
  if (!model || !model->classification_gate) {
    throw UsageError(
        "--gate-threshold: the model has no classification gate (a model of "
        "`train --surveys`, or the default model, has one)");
  }
  model->classification_gate->threshold = *threshold;
}

}  // namespace sonarloop::tools
