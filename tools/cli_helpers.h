#pragma once
// Small helpers shared by the sonarloop subcommands: comma lists and a Ctrl-C stop flag.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "atr/chip_preprocess.h"
#include "atr/subspace_classifier.h"
#include "autonomy/survey.h"
#include "drivers/net/host_port.h"
#include "mission/agent_setup.h"
#include "sim/render/chip_renderer.h"
#include "sim/render/ping_renderer.h"
#include "tools/args.h"

namespace sonarloop::tools {

// A counter as printf's %llu wants it.
inline unsigned long long ull(std::uint64_t v) {
  return static_cast<unsigned long long>(v);
}

// "a, b,,c" -> {"a", "b", "c"}: items trimmed of blanks and tabs, empty items dropped.
std::vector<std::string> split_comma_list(const std::string& text);

// Installs a SIGINT / SIGTERM handler that sets the stop flag and then resets itself
// (SA_RESETHAND), so that a second Ctrl-C ends the process at once. Clears the flag.
void install_stop_flag();
// Whether SIGINT or SIGTERM arrived since install_stop_flag(). Async-signal-safe to poll.
bool stop_requested();
// The signal that asked to stop (SIGINT or SIGTERM), 0 if none.
int stop_signal();

// Whether a command-line value names a YAML file (ends in .yaml or .yml) rather than a preset.
bool is_yaml_path(const std::string& s);

// --seabed of dataset and sweep: a comma list of built-in seabed kinds (flat, ripples, clutter,
// rocky) or scenario files NAME.yaml (their seed, water and seabed; named NAME). Throws
// UsageError for an unknown kind or a name listed twice (a bad file: config::ConfigError).
std::vector<render::DatasetSeabed> dataset_seabeds_option(const std::string& text);

// --area N0,E0,N1,E1 of autonomy and mission: the survey rectangle's south-west and north-east
// corners in metres; nullopt when not given. Throws UsageError for a malformed value.
std::optional<autonomy::SurveyArea> area_option(const Args& args);

// The agent's options that autonomy and mission share: --area, --area-margin, --line-spacing,
// --pass-range, --threshold, --no-relook, --relook-all, --max-relooks, --relook-timing
// after-survey|immediate and --relook-budget F (a fraction of the survey's time, or "none").
// Throws UsageError.
mission::AgentOverrides agent_options(const Args& args);

// --renderer profile|raytrace (default profile); a UsageError names the choices.
render::RendererKind renderer_option(const Args& args);

// --imc udp:HOST:PORT (IMC packets to that address; the port must not be 0); nullopt without it.
std::optional<net::HostPort> imc_option(const Args& args);
// --imc-system ID (decimal or 0x hex, 1..0xFFFE; default emulator::kDefaultImcSystem).
std::uint16_t imc_system_option(const Args& args);

// The chip pre-processing options of train and sweep (atr/chip_preprocess.h): --crop F,
// --multilook K, --levels db|above_seabed|below_seabed|three_level, --threshold-db T. The
// command must declare them. Throws UsageError for a value out of range. --crop auto (the crop
// of atr::adaptive_crop_fraction, per resolution) sets *crop_auto, and is an error when
// crop_auto is null.
atr::ChipPreprocess preprocess_options(const Args& args, bool* crop_auto = nullptr);
// --levels alone (train --surveys), `fallback` when absent.
atr::ChipLevels levels_option(const Args& args, atr::ChipLevels fallback);

// --fuse-levels L[,L...] (train): further readings of every chip (atr::Model views), each `base`
// with another levels mode; "none" for none. `defaults` when the option is absent.
std::vector<atr::ChipPreprocess> fused_levels_option(
    const Args& args, const atr::ChipPreprocess& base,
    const std::vector<atr::ChipLevels>& defaults = {});

// "above_seabed + below_seabed (fused)" or the primary reading's label alone.
std::string model_readings_label(const atr::Model& m);

}  // namespace sonarloop::tools
