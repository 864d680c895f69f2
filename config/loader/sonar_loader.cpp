#include "config/loader/sonar_loader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "config/loader/units_text.h"

namespace sonarloop::config {
namespace {

using acoustics::BottomModel;
using acoustics::TvgLaw;
using render::AlongTrackModel;
using render::SampleType;
using render::SonarDesc;
using render::SpeckleModel;

// Every key of a sonar map, in the order of config/reference.yaml (and of "allowed" lists).
constexpr std::array<std::string_view, 30> kSonarKeys{"name",
                                                      "preset",
                                                      "frequency_khz",
                                                      "source_level_db",
                                                      "pulse_length_us",
                                                      "chirp_bandwidth_khz",
                                                      "array_length_m",
                                                      "array_height_m",
                                                      "depression_deg",
                                                      "max_range_m",
                                                      "bin_size_cm",
                                                      "ping_period_s",
                                                      "along_track",
                                                      "along_track_resolution_cm",
                                                      "sample_type",
                                                      "tvg",
                                                      "gain_db",
                                                      "bottom_model",
                                                      "lambert_mu_db",
                                                      "target_specular_fraction",
                                                      "target_rms_slope",
                                                      "speckle",
                                                      "noise",
                                                      "speckle_model",
                                                      "raw_samples_per_bin",
                                                      "downsample",
                                                      "noise_floor_db_fs",
                                                      "ringdown_us",
                                                      "rays_per_bin",
                                                      "along_track_rays"};

const std::string kMapAllowed = "a map of sonar keys (config/reference.yaml, sonar:)";

// The chirp's range resolution c/(2B) may span at most this many range bins: finer bins only
// oversample the blur the renderer applies over round(resolution / bin) bins.
constexpr double kMaxBinsPerChirpResolution = 4.0;
// Relative slack of the cross-field comparisons, so that values exactly on a bound (written in
// decimal, converted to SI in binary) are accepted.
constexpr double kRuleSlack = 1e-12;

// --- YAML units (units_text.h) --------------------------------------------------------------

// `key` in YAML unit `u`, converted to SI; the base (preset) value, untouched, when not set.
double get_si(const Field& f, std::string_view key, double base_si, YamlUnit u, const Range& r) {
  const Field c = f.child(key);
  return c.present() ? to_si(c.as_double(r), u) : base_si;
}

double get_plain(const Field& f, std::string_view key, double base, const Range& r) {
  const Field c = f.child(key);
  return c.present() ? c.as_double(r) : base;
}

// --- words -----------------------------------------------------------------------------------

template <class T>
struct Word {
  std::string_view text;
  T value;
};

template <class T, std::size_t N>
NameTable<T> word_table(std::string noun, const std::array<Word<T>, N>& words) {
  NameTable<T> t;
  t.noun = std::move(noun);
  for (const auto& w : words)
    t.names.emplace_back(w.text);
  t.allowed = join_names(t.names);
  t.find = [words](std::string_view s) -> std::optional<T> {
    for (const auto& w : words) {
      if (w.text == s) return w.value;
    }
    return std::nullopt;
  };
  return t;
}

template <class T, std::size_t N>
std::string_view word_of(const std::array<Word<T>, N>& words, T value) {
  for (const auto& w : words) {
    if (w.value == value) return w.text;
  }
  return "?";
}

// SonarDesc::tvg is optional: empty = auto (the law follows the along-track model)
enum class TvgChoice { kAuto, kArea, kPoint, kSpherical };

constexpr std::array<Word<SpeckleModel>, 2> kSpeckleModelWords{
    {{"per_bin", SpeckleModel::kPerBin}, {"pulse", SpeckleModel::kPulse}}};
constexpr std::array<Word<acoustics::Downsample>, 3> kDownsampleWords{
    {{"rms", acoustics::Downsample::kRms},
     {"max", acoustics::Downsample::kMax},
     {"decimate", acoustics::Downsample::kDecimate}}};
constexpr std::array<Word<AlongTrackModel>, 2> kAlongTrackWords{
    {{"beam", AlongTrackModel::kBeam}, {"strip", AlongTrackModel::kStrip}}};
constexpr std::array<Word<SampleType>, 4> kSampleTypeWords{{{"uint8", SampleType::kUint8},
                                                            {"uint16", SampleType::kUint16},
                                                            {"int16", SampleType::kInt16},
                                                            {"float32", SampleType::kFloat32}}};
constexpr std::array<Word<TvgChoice>, 4> kTvgWords{{{"auto", TvgChoice::kAuto},
                                                    {"area", TvgChoice::kArea},
                                                    {"point", TvgChoice::kPoint},
                                                    {"spherical", TvgChoice::kSpherical}}};
constexpr std::array<Word<BottomModel>, 2> kBottomWords{
    {{"apl", BottomModel::kApl}, {"lambert", BottomModel::kLambert}}};

TvgChoice tvg_choice(const std::optional<TvgLaw>& law) {
  if (!law) return TvgChoice::kAuto;
  switch (*law) {
    case TvgLaw::kArea:
      return TvgChoice::kArea;
    case TvgLaw::kPoint:
      return TvgChoice::kPoint;
    case TvgLaw::kSpherical:
      return TvgChoice::kSpherical;
  }
  return TvgChoice::kAuto;
}

std::optional<TvgLaw> tvg_law(TvgChoice c) {
  switch (c) {
    case TvgChoice::kAuto:
      return std::nullopt;
    case TvgChoice::kArea:
      return TvgLaw::kArea;
    case TvgChoice::kPoint:
      return TvgLaw::kPoint;
    case TvgChoice::kSpherical:
      return TvgLaw::kSpherical;
  }
  return std::nullopt;
}

const NameTable<SpeckleModel>& speckle_model_names() {
  static const auto t = word_table("speckle model", kSpeckleModelWords);
  return t;
}
const NameTable<acoustics::Downsample>& downsample_names() {
  static const auto t = word_table("downsampling", kDownsampleWords);
  return t;
}
const NameTable<AlongTrackModel>& along_track_names() {
  static const auto t = word_table("known along-track model", kAlongTrackWords);
  return t;
}
const NameTable<SampleType>& sample_type_names() {
  static const auto t = word_table("sample type", kSampleTypeWords);
  return t;
}
const NameTable<TvgChoice>& tvg_names() {
  static const auto t = word_table("TVG law", kTvgWords);
  return t;
}
const NameTable<BottomModel>& bottom_model_names() {
  static const auto t = word_table("bottom model", kBottomWords);
  return t;
}

// Preset names; `allowed` is the text of the allowed list.
NameTable<std::string> preset_table(std::string allowed) {
  NameTable<std::string> t;
  t.noun = "sonar preset";
  t.names = builtin_sonar_names();
  t.allowed = std::move(allowed);
  t.find = [](std::string_view s) -> std::optional<std::string> {
    for (const auto& [name, text] : builtin_sonar_presets()) {
      if (name == s) return name;
    }
    return std::nullopt;
  };
  return t;
}

const NameTable<std::string>& preset_key_names() {
  static const auto t = preset_table(join_names(builtin_sonar_names()));
  return t;
}

const NameTable<std::string>& preset_node_names() {
  static const auto t = preset_table(join_names(builtin_sonar_names()) + ", or " + kMapAllowed);
  return t;
}

// --- messages --------------------------------------------------------------------------------

// a bound for an "allowed" text, rounded outwards at 4 decimals so that it satisfies the rule
std::string at_least(double v) {
  return format_number(std::ceil(v * 1e4) / 1e4);
}
std::string at_most(double v) {
  return format_number(std::floor(v * 1e4) / 1e4);
}

// The key a broken rule between two keys is reported at: the first one this map sets (the
// other's value came from the preset). Returns 0 or 1.
int blamed(const Field& f, std::string_view first, std::string_view second) {
  if (f.child(first).present()) return 0;
  return f.child(second).present() ? 1 : 0;
}

// Range samples per side, as make_sonar_setup counts them (sim/render/sonar.cpp): whole bins
// within max_range_m, with a 1e-9 bin allowance for decimal ranges. Kept as a double: the ratio
// may be far beyond int before the limit is checked.
double samples_per_side(double max_range_m, double bin_size_m) {
  return std::floor(max_range_m / bin_size_m + 1e-9);
}

// --- the rules beyond per-key ranges (see sonar_loader.h) ------------------------------------

void check_rules(const Field& f, const SonarDesc& d) {
  // raw samples are the pulse model's: per-bin speckle has one value per bin
  if (d.raw_samples_per_bin > 1 && d.speckle_model != SpeckleModel::kPulse) {
    f.child("raw_samples_per_bin")
        .fail(std::to_string(d.raw_samples_per_bin) + " raw samples per bin with speckle_model " +
                  std::string(word_of(kSpeckleModelWords, d.speckle_model)),
              "1, or speckle_model: pulse (whose field is drawn on the raw samples)");
  }
  const double c = kNominalSoundSpeed_m_s;
  const double range_m = d.max_range_m;
  // the values as the user wrote them (or would write them)
  const std::string bin_cm = unit_text(d.bin_size_m, YamlUnit::kCentimetre);
  const std::string f_khz = unit_text(d.frequency_hz, YamlUnit::kKilohertz);
  const std::string xtf_note = "at most " + std::to_string(kMaxSamplesPerSide) +
                               " samples per side, the XTF WORD-safe limit";

  // bin below the maximum range
  if (!(d.bin_size_m < range_m)) {
    if (blamed(f, "bin_size_cm", "max_range_m") == 0) {
      f.child("bin_size_cm")
          .fail(bin_cm + " is not below max_range_m " + format_number(range_m),
                "below max_range_m (" + format_number(range_m * 1e2) + " cm)");
    }
    f.child("max_range_m")
        .fail(format_number(range_m) + " is not above the range bin (bin_size_cm " + bin_cm + ")",
              "more than " + format_number(d.bin_size_m) + " (bin_size_cm / 100)");
  }

  // samples per side
  const double samples = samples_per_side(range_m, d.bin_size_m);
  if (samples > kMaxSamplesPerSide) {
    const std::string n = format_number(samples);
    if (blamed(f, "bin_size_cm", "max_range_m") == 0) {
      f.child("bin_size_cm")
          .fail(bin_cm + " gives " + n + " samples per side over max_range_m " +
                    format_number(range_m),
                ">= " + at_least(range_m * 1e2 / kMaxSamplesPerSide) + " for max_range_m " +
                    format_number(range_m) + " (" + xtf_note + ")");
    }
    f.child("max_range_m")
        .fail(
            format_number(range_m) + " gives " + n + " samples per side with bin_size_cm " + bin_cm,
            "<= " + at_most(kMaxSamplesPerSide * d.bin_size_m) + " for bin_size_cm " + bin_cm +
                " (" + xtf_note + ")");
  }

  // a ping period no shorter than the two-way travel time of the maximum range: the echo of
  // max_range_m (2·R/c later) must be back before the next ping goes out
  const double two_way_s = 2.0 * range_m / c;
  if (d.ping_period_s > 0.0 && d.ping_period_s < two_way_s * (1.0 - kRuleSlack)) {
    const std::string period = format_number(d.ping_period_s);
    const std::string why = " (c = " + format_number(c) +
                            " m/s): the echo from the maximum range must return before the next "
                            "ping";
    if (blamed(f, "ping_period_s", "max_range_m") == 0) {
      f.child("ping_period_s")
          .fail(period + " s is shorter than the two-way travel time 2 max_range_m / c = " +
                    approx(two_way_s) + " s of max_range_m " + format_number(range_m) + why,
                "0 (auto: 2 max_range_m / c), or " + at_least(two_way_s) +
                    " .. 10 for max_range_m " + format_number(range_m));
    }
    f.child("max_range_m")
        .fail(format_number(range_m) + " has a two-way travel time 2 max_range_m / c = " +
                  approx(two_way_s) + " s, longer than ping_period_s " + period + why,
              "<= " + at_most(d.ping_period_s * c / 2.0) + " for ping_period_s " + period +
                  "; or ping_period_s 0 (auto)");
  }

  // the array must be longer than a wavelength to form a beam
  const double wavelength_m = c / d.frequency_hz;
  if (!(wavelength_m < d.array_length_m)) {  // strict: equal lengths form no beam either
    const std::string why = " (c = " + format_number(c) + " m/s): the array would form no beam";
    if (blamed(f, "array_length_m", "frequency_khz") == 0) {
      f.child("array_length_m")
          .fail(format_number(d.array_length_m) + " is not longer than the wavelength c/f = " +
                    approx(wavelength_m) + " m at frequency_khz " + f_khz + why,
                "more than " + at_least(wavelength_m) + " for frequency_khz " + f_khz);
    }
    f.child("frequency_khz")
        .fail(f_khz + " has a wavelength c/f = " + approx(wavelength_m) +
                  " m, not shorter than array_length_m " + format_number(d.array_length_m) + why,
              "more than " + at_least(c / d.array_length_m / 1e3) + " for array_length_m " +
                  format_number(d.array_length_m));
  }

  if (d.chirp_bandwidth_hz > 0.0) {
    const std::string b_khz = unit_text(d.chirp_bandwidth_hz, YamlUnit::kKilohertz);
    // the band f ± B/2 stays above 0 Hz
    if (!(d.chirp_bandwidth_hz < 2.0 * d.frequency_hz)) {
      const std::string why = " (the band frequency +/- bandwidth/2 must stay above 0 Hz)";
      if (blamed(f, "chirp_bandwidth_khz", "frequency_khz") == 0) {
        f.child("chirp_bandwidth_khz")
            .fail(b_khz + " is not below twice frequency_khz " + f_khz,
                  "0 (CW), or below " + approx(2.0 * d.frequency_hz / 1e3) + why);
      }
      f.child("frequency_khz")
          .fail(f_khz + " is not above half of chirp_bandwidth_khz " + b_khz,
                "more than " + approx(d.chirp_bandwidth_hz / 2e3) + why);
    }
    // range resolution c/(2B) at most kMaxBinsPerChirpResolution bins
    // (docs/physics.md §3: chirp of bandwidth B after matched filtering, δR = c/(2B))
    const double resolution_m = c / (2.0 * d.chirp_bandwidth_hz);
    const double limit_m = kMaxBinsPerChirpResolution * d.bin_size_m;
    if (resolution_m > limit_m * (1.0 + kRuleSlack)) {
      const std::string res_cm = approx(from_si(resolution_m, YamlUnit::kCentimetre));
      const std::string min_b_khz =
          at_least(c / (2.0 * limit_m) / 1e3);  // B for which c/(2B) = 4 bins
      const std::string min_bin_cm =
          at_least(from_si(resolution_m, YamlUnit::kCentimetre) / kMaxBinsPerChirpResolution);
      const std::string bins = format_number(kMaxBinsPerChirpResolution);
      if (blamed(f, "chirp_bandwidth_khz", "bin_size_cm") == 0) {
        f.child("chirp_bandwidth_khz")
            .fail(b_khz + " gives a range resolution c/(2B) = " + res_cm +
                      " cm (c = " + format_number(c) + " m/s), coarser than " + bins +
                      " range bins of bin_size_cm " + bin_cm,
                  "0 (CW), or >= " + min_b_khz + " for bin_size_cm " + bin_cm +
                      "; or larger bins (bin_size_cm >= " + min_bin_cm + ")");
      }
      f.child("bin_size_cm")
          .fail(bin_cm + " is finer than 1/" + bins +
                    " of the chirp's range resolution c/(2B) = " + res_cm +
                    " cm (chirp_bandwidth_khz " + b_khz + ", c = " + format_number(c) + " m/s)",
                ">= " + min_bin_cm +
                    " for this chirp; or a wider chirp (chirp_bandwidth_khz >= " + min_b_khz + ")");
    }
  }
}

// --- parsing ---------------------------------------------------------------------------------

enum class Source { kUser, kBuiltin };

SonarDesc read_sonar_map(const Field& f, Source source) {
  f.expect_map(kMapAllowed);
  for (std::string_view key : kSonarKeys)
    f.declare({key});
  SonarDesc base;  // built-in presets set every key, so these defaults never show
  if (source == Source::kBuiltin) {
    if (f.has("preset")) {
      f.child("preset").fail("is set in a built-in preset",
                             "no preset key (a built-in preset sets every key itself)");
    }
    for (std::string_view key : kSonarKeys) {
      if (key != "preset" && !f.has(key)) {
        f.child(key).fail("is not set", "every sonar key set in a built-in preset");
      }
    }
  } else {
    const Field p = f.child("preset");
    base = builtin_sonar(p.present() ? p.as_enum(preset_key_names())
                                     : std::string(kDefaultSonarPreset));
  }

  SonarDesc d = base;
  d.name = f.get_string("name", base.name);
  if (d.name.empty()) d.name = base.name;
  d.frequency_hz =
      get_si(f, "frequency_khz", base.frequency_hz, YamlUnit::kKilohertz, Range::closed(50, 1000));
  d.source_level_db =
      get_plain(f, "source_level_db", base.source_level_db, Range::closed(150, 250));
  d.pulse_length_s = get_si(f, "pulse_length_us", base.pulse_length_s, YamlUnit::kMicrosecond,
                            Range::closed(0, 10000).with_note("0 = auto"));
  d.chirp_bandwidth_hz = get_si(f, "chirp_bandwidth_khz", base.chirp_bandwidth_hz,
                                YamlUnit::kKilohertz, Range::closed(0, 500).with_note("0 = CW"));
  d.array_length_m = get_plain(f, "array_length_m", base.array_length_m, Range::closed(0.02, 10));
  d.array_height_m = get_plain(f, "array_height_m", base.array_height_m, Range::closed(0.001, 1));
  d.depression_deg = get_plain(f, "depression_deg", base.depression_deg, Range::closed(0, 60));
  d.max_range_m = get_plain(f, "max_range_m", base.max_range_m, Range::closed(1, 1000));
  d.bin_size_m =
      get_si(f, "bin_size_cm", base.bin_size_m, YamlUnit::kCentimetre, Range::closed(1, 100));
  d.ping_period_s =
      get_plain(f, "ping_period_s", base.ping_period_s, Range::closed(0, 10).with_note("0 = auto"));
  d.along_track = f.get_enum("along_track", base.along_track, along_track_names());
  d.along_track_resolution_m =
      get_si(f, "along_track_resolution_cm", base.along_track_resolution_m, YamlUnit::kCentimetre,
             Range::closed(0, 500).with_note("0 = bin_size_cm"));
  d.sample_type = f.get_enum("sample_type", base.sample_type, sample_type_names());
  d.tvg = tvg_law(f.get_enum("tvg", tvg_choice(base.tvg), tvg_names()));
  d.gain_db = get_plain(f, "gain_db", base.gain_db, Range::closed(-100, 100));
  d.bottom_model = f.get_enum("bottom_model", base.bottom_model, bottom_model_names());
  d.lambert_mu_db = get_plain(
      f, "lambert_mu_db", base.lambert_mu_db,
      Range::closed(-60, -4.97).with_note("-4.97: about 10 log10(1/pi), the energy bound"));
  d.target_specular_fraction =
      get_plain(f, "target_specular_fraction", base.target_specular_fraction,
                Range::closed(0, 1).with_note("0 = Lambert facets only, as the paper"));
  d.target_rms_slope =
      get_plain(f, "target_rms_slope", base.target_rms_slope, Range::closed(0.02, 0.5));
  d.speckle = f.get_bool("speckle", base.speckle);
  d.noise = f.get_bool("noise", base.noise);
  d.speckle_model = f.get_enum("speckle_model", base.speckle_model, speckle_model_names());
  d.raw_samples_per_bin = f.get_int("raw_samples_per_bin", base.raw_samples_per_bin, 1, 16);
  d.downsample = f.get_enum("downsample", base.downsample, downsample_names());
  d.noise_floor_db_fs =
      get_plain(f, "noise_floor_db_fs", base.noise_floor_db_fs,
                Range::closed(-150, 0).with_note("dB re full scale after TVG and gain; 0 = none"));
  d.ringdown_s = get_si(f, "ringdown_us", base.ringdown_s, YamlUnit::kMicrosecond,
                        Range::closed(0, 10000).with_note("0 = none"));
  d.rays_per_bin = f.get_int("rays_per_bin", base.rays_per_bin, 0, 64);
  d.along_track_rays = f.get_int("along_track_rays", base.along_track_rays, 0, 256);

  f.finish();
  check_rules(f, d);
  return d;
}

}  // namespace

std::vector<std::string> builtin_sonar_names() {
  std::vector<std::string> names;
  for (const auto& [name, text] : builtin_sonar_presets())
    names.push_back(name);
  return names;
}

SonarDesc builtin_sonar(std::string_view name) {
  for (const auto& entry : builtin_sonar_presets()) {
    if (entry.first != name) continue;
    const std::string file = "config/sonars/" + entry.first + ".yaml (built in)";
    // (no structured binding: clang 14 cannot capture one in the lambda)
    const auto& text = entry.second;
    return with_yaml_errors(
        file, [&] { return read_sonar_map(parse_document(text, file), Source::kBuiltin); });
  }
  const auto names = builtin_sonar_names();
  throw ConfigError(ConfigIssue{"<built-in sonars>", "preset",
                                "'" + std::string(name) + "' is not a sonar preset",
                                join_names(names), closest_name(name, names).value_or(""), 0, 0});
}

SonarDesc parse_sonar_node(const Field& f) {
  if (f.is_null()) return builtin_sonar(kDefaultSonarPreset);
  if (f.is_scalar()) return builtin_sonar(f.as_enum(preset_node_names()));
  if (!f.is_map()) {
    f.fail(f.describe_value() + " is not a sonar preset name or a map",
           preset_node_names().allowed);
  }
  return read_sonar_map(f, Source::kUser);
}

SonarDesc parse_sonar(const std::string& yaml_text, const std::string& source_name) {
  return with_yaml_errors(source_name,
                          [&] { return parse_sonar_node(parse_document(yaml_text, source_name)); });
}

SonarDesc load_sonar(const std::string& path) {
  return parse_sonar(read_text_file(path), path);
}

std::string format_sonar_yaml(const SonarDesc& d, int indent) {
  const std::string pad(static_cast<std::size_t>(std::max(indent, 0)), ' ');
  const auto num = [](double v) { return format_number(v); };
  YAML::Emitter name;
  name << YAML::DoubleQuoted << d.name;
  std::string out;
  append_yaml_line(out, pad, "name", name.c_str());
  append_yaml_line(out, pad, "frequency_khz", unit_text(d.frequency_hz, YamlUnit::kKilohertz));
  append_yaml_line(out, pad, "source_level_db", num(d.source_level_db));
  append_yaml_line(out, pad, "pulse_length_us",
                   unit_text(d.pulse_length_s, YamlUnit::kMicrosecond));
  append_yaml_line(out, pad, "chirp_bandwidth_khz",
                   unit_text(d.chirp_bandwidth_hz, YamlUnit::kKilohertz));
  append_yaml_line(out, pad, "array_length_m", num(d.array_length_m));
  append_yaml_line(out, pad, "array_height_m", num(d.array_height_m));
  append_yaml_line(out, pad, "depression_deg", num(d.depression_deg));
  append_yaml_line(out, pad, "max_range_m", num(d.max_range_m));
  append_yaml_line(out, pad, "bin_size_cm", unit_text(d.bin_size_m, YamlUnit::kCentimetre));
  append_yaml_line(out, pad, "ping_period_s", num(d.ping_period_s));
  append_yaml_line(out, pad, "along_track", word_of(kAlongTrackWords, d.along_track));
  append_yaml_line(out, pad, "along_track_resolution_cm",
                   unit_text(d.along_track_resolution_m, YamlUnit::kCentimetre));
  append_yaml_line(out, pad, "sample_type", word_of(kSampleTypeWords, d.sample_type));
  append_yaml_line(out, pad, "tvg", word_of(kTvgWords, tvg_choice(d.tvg)));
  append_yaml_line(out, pad, "gain_db", num(d.gain_db));
  append_yaml_line(out, pad, "bottom_model", word_of(kBottomWords, d.bottom_model));
  append_yaml_line(out, pad, "lambert_mu_db", num(d.lambert_mu_db));
  append_yaml_line(out, pad, "target_specular_fraction", num(d.target_specular_fraction));
  append_yaml_line(out, pad, "target_rms_slope", num(d.target_rms_slope));
  append_yaml_line(out, pad, "speckle", d.speckle ? "true" : "false");
  append_yaml_line(out, pad, "noise", d.noise ? "true" : "false");
  append_yaml_line(out, pad, "speckle_model", word_of(kSpeckleModelWords, d.speckle_model));
  append_yaml_line(out, pad, "raw_samples_per_bin", std::to_string(d.raw_samples_per_bin));
  append_yaml_line(out, pad, "downsample", word_of(kDownsampleWords, d.downsample));
  append_yaml_line(out, pad, "noise_floor_db_fs", num(d.noise_floor_db_fs));
  append_yaml_line(out, pad, "ringdown_us", unit_text(d.ringdown_s, YamlUnit::kMicrosecond));
  append_yaml_line(out, pad, "rays_per_bin", std::to_string(d.rays_per_bin));
  append_yaml_line(out, pad, "along_track_rays", std::to_string(d.along_track_rays));
  return out;
}

}  // namespace sonarloop::config
