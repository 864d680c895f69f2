#pragma once
// Loads a sidescan sonar description (render::SonarDesc) from YAML: a standalone sonar file, the
// `sonar:` section of a scenario, or one of the built-in presets (config/sonars/*.yaml, compiled
// into the binary). Every key, its default and its range is documented in config/reference.yaml
// under `sonar:`. Keys carry YAML-friendly units in their names (frequency_khz, pulse_length_us,
// bin_size_cm, ...); the result is in SI units.
//
// A sonar node is either
//   - a preset name (a scalar): that built-in preset, unchanged;
//   - a map: it starts from the preset named by its `preset` key (default: kDefaultSonarPreset)
//     and every other key given overrides the preset's value;
//   - absent or empty: the default preset.
//
// Rules beyond the per-key ranges (the speed of sound is the nominal kNominalSoundSpeed_m_s,
// because a sonar is described independently of the water it is used in):
// - bin_size_cm / 100 < max_range_m;
// - floor(max_range_m / bin size) <= 65535 samples per side: the XTF ping channel's NumSamples is
//   a DWORD, but 65535 keeps the count within a 16-bit WORD, which some XTF readers assume
//   (the WORD-safe limit);
// - a chirp (chirp_bandwidth_khz > 0): its range resolution c/(2B) at most 4 range bins (finer
//   bins only oversample the blur), and B < 2·frequency (the band f ± B/2 stays above 0 Hz);
// - the wavelength c/f shorter than array_length_m (otherwise the array forms no beam);
// - ping_period_s 0 (auto) or at least the two-way travel time 2·max_range_m/c (the echo of the
//   maximum range is back before the next ping; a shorter period is physically impossible for
//   one sidescan and would make `run` attempt absurd ping rates).
// When a rule fails, the error names the key of the pair that this map sets (the other value
// came from the preset), and the message says what would satisfy the rule.
//
// Built-in presets must set every key (checked when they are parsed) so that they do not depend
// on the defaults of render::SonarDesc.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "config/loader/yaml_fields.h"
#include "sim/render/sonar.h"

namespace sonarloop::config {

// The preset a sonar map starts from when it names none (also the scenario default).
inline constexpr std::string_view kDefaultSonarPreset = "pailhas_strip";

// Nominal speed of sound for the sonar's cross-field rules, m/s. Sea water ranges about
// 1450-1550 m/s (docs/physics.md §1); the renderer uses the scenario water's
// Francois-Garrison value.
inline constexpr double kNominalSoundSpeed_m_s = 1500.0;

// At most this many range samples per side (see above).
inline constexpr int kMaxSamplesPerSide = 65535;

// The built-in presets, (name, YAML text), in the order listed in config/CMakeLists.txt.
// Generated at build time from config/sonars/<name>.yaml.
const std::vector<std::pair<std::string, std::string>>& builtin_sonar_presets();

// The names of builtin_sonar_presets(), in order.
std::vector<std::string> builtin_sonar_names();

// A built-in preset, parsed. An unknown name -> ConfigError listing the available names.
render::SonarDesc builtin_sonar(std::string_view name);

// Parses the sonar node `f` (a preset name, a map, or absent/empty: see above). Reports unknown
// keys of the sonar map itself.
render::SonarDesc parse_sonar_node(const Field& f);

// Parses a standalone sonar document; `source_name` is used in messages.
render::SonarDesc parse_sonar(const std::string& yaml_text, const std::string& source_name);

// Reads and parses a standalone sonar file. A missing file -> "<path>: (file): no such file".
render::SonarDesc load_sonar(const std::string& path);

// The sonar as a YAML block map with every key in YAML units (no preset key), each line
// prefixed by `indent` spaces. Each number is the shortest text that converts back to the same
// SI value, so parse_sonar reads a loaded sonar back bit for bit (a value set in code that no
// decimal converts back to exactly comes back within an ulp or so).
std::string format_sonar_yaml(const render::SonarDesc& sonar, int indent = 0);

}  // namespace sonarloop::config
