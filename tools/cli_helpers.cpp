#include "tools/cli_helpers.h"

#include <signal.h>

#include <atomic>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>

#include "config/loader/scenario_loader.h"
#include "emulator/imc_device.h"

namespace sonarloop::tools {
namespace {

namespace fs = std::filesystem;

std::atomic<int> g_stop_signal{0};  // the signal that asked to stop, 0: none
static_assert(std::atomic<int>::is_always_lock_free, "set from a signal handler");

void on_stop_flag_signal(int sig) {
  g_stop_signal.store(sig);
}

}  // namespace

bool is_yaml_path(const std::string& s) {
  const auto ext = fs::path(s).extension().string();
  return ext == ".yaml" || ext == ".yml";
}

std::vector<render::DatasetSeabed> dataset_seabeds_option(const std::string& text) {
  std::vector<render::DatasetSeabed> out;
  std::set<std::string> names;
  for (const std::string& item : split_comma_list(text)) {
    render::DatasetSeabed s;
    if (is_yaml_path(item)) {
      s.desc = config::load_scenario(item).scene;  // ConfigError names the file and key
      s.name = fs::path(item).stem().string();
    } else {
      try {
        s = render::builtin_dataset_seabed(item);
      } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--seabed: ") + e.what() +
                         "; or give a scenario file NAME.yaml");
      }
    }
    if (!names.insert(s.name).second) {
      throw UsageError("--seabed: the seabed '" + s.name + "' is listed twice");
    }
    out.push_back(std::move(s));
  }
  if (out.empty()) throw UsageError("--seabed: no seabed given");
  return out;
}

std::vector<std::string> split_comma_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto first = item.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    out.push_back(item.substr(first, item.find_last_not_of(" \t") - first + 1));
  }
  return out;
}

void install_stop_flag() {
  g_stop_signal.store(0);
  struct sigaction action {};
  action.sa_handler = on_stop_flag_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool stop_requested() {
  return g_stop_signal.load() != 0;
}

int stop_signal() {
  return g_stop_signal.load();
}

render::RendererKind renderer_option(const Args& args) {
  const std::string name = args.get_or("--renderer", "profile");
  const auto kind = render::parse_renderer(name);
  if (!kind) throw UsageError("--renderer: '" + name + "' is not one of profile, raytrace");
  return *kind;
}

std::optional<net::HostPort> imc_option(const Args& args) {
  const auto text = args.get("--imc");
  if (!text) return std::nullopt;
  if (text->rfind("udp:", 0) != 0)
    throw UsageError("--imc " + *text + ": expected udp:HOST:PORT (IMC over UDP)");
  net::HostPort hp;
  try {
    hp = net::parse_host_port(text->substr(4));
  } catch (const std::invalid_argument& e) {
    throw UsageError("--imc " + *text + ": " + e.what());
  }
  if (hp.port == 0) throw UsageError("--imc " + *text + ": the port must not be 0");
  return hp;
}

std::uint16_t imc_system_option(const Args& args) {
  const auto text = args.get("--imc-system");
  if (!text) return emulator::kDefaultImcSystem;
  std::size_t used = 0;
  unsigned long v = 0;
  try {
    v = std::stoul(*text, &used, 0);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text->size() || v < 1 || v > 0xFFFE)
    throw UsageError("--imc-system " + *text + ": expected an IMC address 1..0xFFFE (e.g. 0x2050)");
  return static_cast<std::uint16_t>(v);
}

namespace {

atr::ChipLevels parse_levels(const std::string& option, const std::string& text) {
  for (auto mode : {atr::ChipLevels::kDb, atr::ChipLevels::kAboveSeabed,
                    atr::ChipLevels::kBelowSeabed, atr::ChipLevels::kThreeLevel}) {
    if (text == atr::chip_levels_name(mode)) return mode;
  }
  throw UsageError(option + ": '" + text +
                   "' is not one of db, above_seabed, below_seabed, three_level");
}

}  // namespace

atr::ChipPreprocess preprocess_options(const Args& args, bool* crop_auto) {
  atr::ChipPreprocess p;
  if (args.get("--crop") == "auto") {
    if (!crop_auto) {
      throw UsageError(
          "--crop auto needs the pixel size, which only sweep knows; give a fraction here");
    }
    *crop_auto = true;
  } else {
    p.crop_fraction = args.get_double("--crop", 0.05, 1.0).value_or(p.crop_fraction);
  }
  p.multilook_px = static_cast<int>(args.get_int("--multilook", 1, 63).value_or(p.multilook_px));
  if (p.multilook_px % 2 == 0)
    throw UsageError("--multilook: the window must be odd (1, 3, 5 ...)");
  if (const auto l = args.get("--levels")) p.levels = parse_levels("--levels", *l);
  p.threshold_db = args.get_double("--threshold-db", 0.1, 59.0).value_or(p.threshold_db);
  return p;
}

atr::ChipLevels levels_option(const Args& args, atr::ChipLevels fallback) {
  const auto l = args.get("--levels");
  return l ? parse_levels("--levels", *l) : fallback;
}

std::vector<atr::ChipPreprocess> fused_levels_option(const Args& args,
                                                     const atr::ChipPreprocess& base,
                                                     const std::vector<atr::ChipLevels>& defaults) {
  std::vector<atr::ChipLevels> levels = defaults;
  if (const auto v = args.get("--fuse-levels")) {
    levels.clear();
    if (*v != "none") {
      for (const std::string& name : split_comma_list(*v))
        levels.push_back(parse_levels("--fuse-levels", name));
    }
  }
  if (levels.size() > atr::kMaxModelViews) {
    throw UsageError("--fuse-levels: at most " + std::to_string(atr::kMaxModelViews) +
                     " further readings");
  }
  std::vector<atr::ChipPreprocess> views;
  for (const atr::ChipLevels l : levels) {
    if (l == base.levels) {
      throw UsageError(std::string("--fuse-levels: ") + atr::chip_levels_name(l) +
                       " is the model's own reading (--levels)");
    }
    atr::ChipPreprocess p = base;
    p.levels = l;
    views.push_back(p);
  }
  return views;
}

std::string model_readings_label(const atr::Model& m) {
  std::string s = atr::preprocess_label(m.preprocess);
  for (const atr::ModelView& v : m.views)
    s += " + " + atr::preprocess_label(v.preprocess);
  if (!m.views.empty()) s += " (readings fused)";
  return s;
}

std::optional<autonomy::SurveyArea> area_option(const Args& args) {
  const auto v = args.get("--area");
  if (!v) return std::nullopt;
  const std::vector<std::string> parts = split_comma_list(*v);
  double x[4];
  bool ok = parts.size() == 4;
  for (std::size_t i = 0; ok && i < 4; ++i) {
    char* end = nullptr;
    x[i] = std::strtod(parts[i].c_str(), &end);
    ok = *end == '\0' && std::isfinite(x[i]);
  }
  if (!ok || !(x[2] > x[0]) || !(x[3] > x[1])) {
    throw UsageError("--area: expected N0,E0,N1,E1 in metres with N1 > N0 and E1 > E0, got '" + *v +
                     "'");
  }
  return autonomy::SurveyArea{{x[0], x[1]}, {x[2], x[3]}};
}

mission::AgentOverrides agent_options(const Args& args) {
  mission::AgentOverrides o;
  o.area = area_option(args);
  o.area_margin_m = args.get_double("--area-margin", 0.0, 1e4).value_or(o.area_margin_m);
  o.line_spacing_m = args.get_double("--line-spacing", 1.0, 1e4).value_or(o.line_spacing_m);
  o.pass_range_m = args.get_double("--pass-range", 1.0, 1000.0);
  o.threshold = args.get_double("--threshold", 0.0, 1e9);
  o.relooks = !args.has("--no-relook");
  o.relook_all = args.has("--relook-all");
  o.max_relooks =
      static_cast<int>(args.get_int("--max-relooks", 0, 1 << 30).value_or(o.max_relooks));
  if (const auto t = args.get("--relook-timing")) {
    if (*t == "after-survey") {
      o.relook_timing = autonomy::RelookTiming::kAfterSurvey;
    } else if (*t == "immediate") {
      o.relook_timing = autonomy::RelookTiming::kImmediate;
    } else {
      throw UsageError("--relook-timing: expected after-survey or immediate, got '" + *t + "'");
    }
  }
  if (const auto b = args.get("--relook-budget")) {
    if (*b == "none") {
      o.relook_budget_fraction = std::numeric_limits<double>::infinity();
    } else {
      o.relook_budget_fraction = *args.get_double("--relook-budget", 0.0, 100.0);
    }
  }
  return o;
}

}  // namespace sonarloop::tools
