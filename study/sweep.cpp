#include "study/sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "atr/chip_deripple.h"
#include "atr/chip_register.h"
#include "atr/shadow_height.h"

namespace sonarloop::study {

// the classifier this study code trains and scores (atr/)
using namespace sonarloop::atr;
namespace {

using targets::TargetType;

// The four targets of Figs. 11 and 15 (Section 3.1), in the paper's order.
const std::vector<TargetType>& four_targets() {
  static const std::vector<TargetType> kTargets{TargetType::kManta, TargetType::kRockan,
                                                TargetType::kCuboid, TargetType::kCylinder};
  return kTargets;
}

// Fig. 11 / 13: 15 resolutions from 3 to 30 cm.
const std::vector<double>& highlight_resolutions_cm() {
  static const std::vector<double> kCm{3, 4, 5, 6, 7, 8, 9, 10, 12, 14, 16, 18, 20, 25, 30};
  return kCm;
}

// Fig. 15: shadows from 5 to 30 cm (shadow chips are 3 x 10 m: 100 x 333 pixels at 3 cm).
const std::vector<double>& shadow_resolutions_cm() {
  static const std::vector<double> kCm{5, 7.5, 10, 12.5, 15, 17.5, 20, 25, 30};
  return kCm;
}

// The stability studies run at the paper's best highlight resolution unless told otherwise.
constexpr double kStabilityResolutionCm = 5.0;

std::string cm_label(double cm) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g cm", cm);
  return buf;
}

SweepCondition base_condition(const SweepSettings& s, double resolution_cm) {
  SweepCondition c;
  c.x_name = "resolution_cm";
  c.x = resolution_cm;
  c.resolution_m = resolution_cm / 100.0;
  c.train_count = s.train_count;
  c.p = s.p;
  c.aspect_sectors = s.aspect_sectors;
  c.preprocess = s.preprocess;
  return c;
}

// One condition per resolution (Figs. 11, 13, 15).
std::vector<SweepCondition> resolution_curve(const SweepSettings& s,
                                             const std::vector<double>& default_cm) {
  std::vector<SweepCondition> out;
  for (double cm : s.resolutions_cm.empty() ? default_cm : s.resolutions_cm) {
    if (s.looks <= 1) {
      out.push_back(base_condition(s, cm));
      continue;
    }
    for (int k = 1; k <= s.looks; ++k) {  // one curve per number of looks fused
      SweepCondition c = base_condition(s, cm);
      c.looks = k;
      c.series = std::to_string(k) + (k == 1 ? " look" : " looks");
      out.push_back(c);
    }
  }
  return out;
}

// A stability study: for each resolution (default 5 cm; the series), one condition per value.
template <class Apply>
std::vector<SweepCondition> stability_curve(const SweepSettings& s, const std::string& x_name,
                                            const std::vector<double>& values, Apply apply) {
  std::vector<SweepCondition> out;
  const std::vector<double> res =
      s.resolutions_cm.empty() ? std::vector<double>{kStabilityResolutionCm} : s.resolutions_cm;
  for (double cm : res) {
    for (double v : values) {
      SweepCondition c = base_condition(s, cm);
      c.series = cm_label(cm);
      c.x_name = x_name;
      c.x = v;
      if (apply(c, v)) out.push_back(c);
    }
  }
  return out;
}

// The pre-processing variants of the ablation: each factor alone, then the combinations.
std::vector<ChipPreprocess> ablation_variants() {
  std::vector<ChipPreprocess> v(1);  // eq. 9 only (the paper)
  const auto add = [&](double crop, int looks, ChipLevels levels) {
    v.push_back(ChipPreprocess{crop, looks, levels, 6.0});
  };
  add(1.0, 3, ChipLevels::kDb);
  add(1.0, 5, ChipLevels::kDb);
  add(1.0, 1, ChipLevels::kAboveSeabed);
  add(1.0, 3, ChipLevels::kThreeLevel);
  add(2.0 / 3.0, 1, ChipLevels::kDb);
  add(0.5, 1, ChipLevels::kDb);
  add(0.4, 1, ChipLevels::kDb);
  add(0.3, 1, ChipLevels::kDb);
  add(0.5, 1, ChipLevels::kAboveSeabed);
  add(0.4, 1, ChipLevels::kAboveSeabed);
  return v;
}

// At 5 and 15 cm (or --resolutions-cm): one series per variant, x = the resolution.
std::vector<SweepCondition> ablation_conditions(const SweepSettings& s) {
  std::vector<SweepCondition> out;
  const std::vector<double> res =
      s.resolutions_cm.empty() ? std::vector<double>{5.0, 15.0} : s.resolutions_cm;
  for (double cm : res) {
    for (const ChipPreprocess& p : ablation_variants()) {
      SweepCondition c = base_condition(s, cm);
      c.series = preprocess_label(p);
      c.preprocess = p;
      out.push_back(c);
    }
  }
  return out;
}

}  // namespace

Chip registration_chip(ChipView chip, const SweepCondition& c, std::uint64_t index, bool test) {
  const int side = std::max(1, static_cast<int>(std::lround(c.window_m / c.resolution_m)));
  ChipPoint centre{0.5 * (chip.height - 1), 0.5 * (chip.width - 1)};
  if (test && c.misregister_m > 0.0) {
    // uniform in a disc of radius misregister_m, from the chip's index (splitmix64)
    std::uint64_t z = index + 0x9E3779B97F4A7C15ull;
    const auto next = [&z] {
      z += 0x9E3779B97F4A7C15ull;
      std::uint64_t x = z;
      x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
      x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
      return static_cast<double>((x ^ (x >> 31)) >> 11) * 0x1.0p-53;
    };
    const double r = c.misregister_m / c.resolution_m * std::sqrt(next());
    const double a = 2.0 * std::numbers::pi * next();
    centre.row += r * std::sin(a);
    centre.col += r * std::cos(a);
  }
  if (c.register_centroid) {
    const int cue = std::max(
        side,
        static_cast<int>(std::lround((c.window_m + kRegistrationCueMargin_m) / c.resolution_m)));
    // the cue window on whole chip pixels (its pixel k is the chip's o + k), so that the
    // centroid maps back exactly
    const double half = 0.5 * (cue - 1);
    const double o_row = static_cast<double>(std::lround(centre.row - half));
    const double o_col = static_cast<double>(std::lround(centre.col - half));
    const Chip window = chip_window(chip, cue, cue, {o_row + half, o_col + half});
    const ChipPoint p = highlight_centroid(window.view());
    centre = {o_row + p.row, o_col + p.col};
  }
  return chip_window(chip, side, side, centre);
}

Chip classifier_chip(const render::ChipImage& c, bool shadow_height, bool deripple) {
  Chip chip;
  chip.width = c.cols;
  chip.height = c.rows;
  chip.pixels.assign(c.pixels.begin(), c.pixels.end());
  if (deripple) chip = deripple_chip(chip.view());
  if (!shadow_height) return chip;
  const ShadowChipGeometry g{c.params.altitude_m, c.params.ground_range_m, c.range_start_m,
                             c.resolution_m};
  return shadow_height_chip(chip.view(), g);
}

LabelledChip labelled_chip(const render::ChipImage& c, bool shadow_height, bool deripple) {
  LabelledChip lc;
  lc.chip = classifier_chip(c, shadow_height, deripple);
  lc.label = std::string(targets::target_type_info(c.params.type).key);
  lc.aspect_deg = c.params.aspect_deg;
  lc.source = "chip " + std::to_string(c.params.index);
  return lc;
}

std::vector<TargetType> fig13_classes(const SweepSettings& s) {
  std::vector<TargetType> out{TargetType::kManta, TargetType::kRockan, TargetType::kCylinder};
  out.insert(out.end(), s.non_mine.begin(), s.non_mine.end());
  return out;
}

bool is_fusion(const SweepExperiment& e) {
  return !e.conditions.empty() && e.conditions.front().fusion != FusionInput::kNone;
}

std::vector<std::string> sweep_experiment_names() {
  return {"fig11",      "fig13", "fig15",    "aspect", "snr",      "altitude",     "burial",
          "train_size", "p",     "open_set", "fusion", "fusion13", "registration", "ablation"};
}

SweepExperiment make_sweep_experiment(const std::string& name, const SweepSettings& s) {
  if (s.looks < 1 || s.looks > kMaxSweepLooks) {
    throw std::invalid_argument("looks " + std::to_string(s.looks) + " is outside 1.." +
                                std::to_string(kMaxSweepLooks));
  }
  SweepExperiment e;
  e.name = name;
  e.classes = four_targets();
  e.test_count = s.test_count;
  for (const auto& b : s.seabeds)
    e.seabed_names.push_back(b.name);
  if (name == "fig11") {
    e.title = "Fig. 11: identification from highlights against pixel resolution";
    e.conditions = resolution_curve(s, highlight_resolutions_cm());
  } else if (name == "fig13") {
    // Sec. 4.1.2: the mine-like Manta, Rockan and cylinder against the non-mine shapes
    e.title = "Fig. 13: mine-like and non-mine targets, identification and mine / non-mine";
    e.classes = fig13_classes(s);
    e.mine_groups = true;
    e.conditions = resolution_curve(s, highlight_resolutions_cm());
  } else if (name == "fig15") {
    e.title = "Fig. 15: identification from shadows against pixel resolution";
    e.kind = chips::ChipKind::kShadow;
    e.conditions = resolution_curve(s, shadow_resolutions_cm());
  } else if (name == "aspect") {
    // the same training chips (twice the usual count, so that an 8-sector subspace still
    // holds ~20 chips) for one subspace per target and for 4 and 8 aspect sectors
    e.title = "Error against target aspect: one subspace per target or one per aspect sector";
    e.aspect_bins = kSweepAspectBins;
    e.conditions =
        stability_curve(s, "aspect_sectors", {1, 4, 8}, [&](SweepCondition& c, double v) {
          c.aspect_sectors = static_cast<int>(v);
          c.train_count = 2 * s.train_count;
          c.series = (v == 1 ? std::string("1 subspace")
                             : std::to_string(static_cast<int>(v)) + " sectors") +
                     " (" + c.series + ")";
          return true;
        });
  } else if (name == "snr") {
    // the renderer's full scale follows the source level (quantise.h), the Mellen noise does
    // not: every dB less is a dB less signal-to-noise ratio in the chip
    e.title = "Stability: source level (signal-to-noise ratio)";
    e.conditions = stability_curve(s, "source_level_db", {210, 190, 170, 160, 150, 140, 130},
                                   [&](SweepCondition& c, double v) {
                                     c.source_level_offset_db = v - s.sonar.source_level_db;
                                     return true;
                                   });
  } else if (name == "altitude") {
    e.title = "Stability: sonar altitude (grazing angle)";
    e.conditions =
        stability_curve(s, "altitude_m", {2, 3, 5, 7, 10, 15, 20}, [](SweepCondition& c, double v) {
          c.altitude_min_m = v;
          c.altitude_max_m = v;
          return true;
        });
  } else if (name == "train_size") {
    e.title = "Stability: training chips per target";
    e.conditions = stability_curve(s, "train_per_class", {5, 10, 20, 40, 80, 160, 320},
                                   [](SweepCondition& c, double v) {
                                     c.train_count = static_cast<int>(v);
                                     return true;
                                   });
  } else if (name == "p") {
    e.title = "Stability and speed: subspace dimension p";
    e.conditions =
        stability_curve(s, "p", {1, 2, 3, 5, 10, 20, 40, 60, 79}, [&](SweepCondition& c, double v) {
          c.p = static_cast<int>(v);
          return c.p < s.train_count;  // rank <= k - 1
        });
  } else if (name == "burial") {
    e.title = "Stability: target burial (tested buried, trained proud)";
    e.classes = fig13_classes(s);
    e.mine_groups = true;
    e.conditions =
        stability_curve(s, "burial_pct", {0, 10, 20, 30, 40, 50}, [](SweepCondition& c, double v) {
          c.burial_fraction = v / 100.0;
          return true;
        });
  } else if (name == "open_set") {
    e.title =
        "Open-set rejection: each of the seven targets left out of training in turn, "
        "then types never trained";
    e.classes = fig13_classes(s);
    e.novel_from = e.classes.size();
    e.classes.insert(e.classes.end(), s.novel.begin(), s.novel.end());
    const std::vector<double> res =
        s.resolutions_cm.empty() ? std::vector<double>{5.0, 15.0} : s.resolutions_cm;
    for (double cm : res) {
      for (int h = -1; h < static_cast<int>(e.classes.size()); ++h) {
        SweepCondition c = base_condition(s, cm);
        c.held_out = h;
        c.reject_quantile = s.reject_quantile;
        c.series =
            h < 0 ? std::string("none held out")
                  : "held out: " +
                        std::string(
                            targets::target_type_info(e.classes[static_cast<std::size_t>(h)]).key);
        e.conditions.push_back(c);
      }
    }
  } else if (name == "fusion" || name == "fusion13") {
    e.title = "Highlight + shadow fusion: the same objects from either chip and from both";
    if (name == "fusion13") {  // fig13's seven, with the mine / non-mine decision
      e.title += " (Fig. 13's seven)";
      e.classes = fig13_classes(s);
      e.mine_groups = true;
    }
    const std::vector<double> res =
        s.resolutions_cm.empty() ? std::vector<double>{5.0, 10.0, 15.0, 20.0} : s.resolutions_cm;
    for (double cm : res) {
      for (const FusionInput input :
           {FusionInput::kHighlight, FusionInput::kShadow, FusionInput::kFused}) {
        for (const FusionNorm norm :
             {FusionNorm::kClassTypical, FusionNorm::kModelTypical, FusionNorm::kLookZScore}) {
          if (input != FusionInput::kFused && norm != FusionNorm::kClassTypical) continue;
          SweepCondition c = base_condition(s, cm);
          c.fusion = input;
          c.fusion_norm = norm;
          c.series = input == FusionInput::kHighlight ? "highlight"
                     : input == FusionInput::kShadow
                         ? "shadow"
                         : std::string("both (") + fusion_norm_name(norm) + ")";
          e.conditions.push_back(c);
        }
      }
    }
  } else if (name == "registration") {
    e.title =
        "Registration: test chips cut off the target's centre, with and without "
        "re-centring on the highlight";
    const std::vector<double> res =
        s.resolutions_cm.empty() ? std::vector<double>{5.0} : s.resolutions_cm;
    for (double cm : res) {
      for (const bool reg : {false, true}) {
        for (const double off : {0.0, 0.1, 0.2, 0.3, 0.5}) {
          SweepCondition c = base_condition(s, cm);
          c.x_name = "misregistration_m";
          c.x = off;
          c.preprocess = ChipPreprocess{};  // the window is the crop
          c.window_m = kMinCroppedSide_m;
          c.misregister_m = off;
          c.register_centroid = reg;
          c.series = std::string(reg ? "centroid-registered" : "as cut") + " " + cm_label(cm);
          e.conditions.push_back(c);
        }
      }
    }
    return e;  // its own window
  } else if (name == "ablation") {
    e.title = "Ablation: chip pre-processing before eq. 9 (highlights)";
    e.conditions = ablation_conditions(s);
    return e;  // its own crops
  } else {
    std::string all;
    for (const auto& n : sweep_experiment_names())
      all += (all.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown experiment '" + name + "' (allowed: " + all + ", all)");
  }
  if (s.crop_auto && e.kind == chips::ChipKind::kHighlight) {
    for (SweepCondition& c : e.conditions) {
      // fusion's shadow model shares the condition: it keeps its whole chip (cmd_sweep)
      c.preprocess.crop_fraction =
          adaptive_crop_fraction(chips::kHighlightChipRange_m, c.resolution_m);
    }
  }
  return e;
}

bool same_training(const SweepCondition& a, const SweepCondition& b) {
  return a.resolution_m == b.resolution_m && a.altitude_min_m == b.altitude_min_m &&
         a.altitude_max_m == b.altitude_max_m &&
         a.source_level_offset_db == b.source_level_offset_db && a.train_count == b.train_count &&
         a.p == b.p && a.aspect_sectors == b.aspect_sectors && a.preprocess == b.preprocess &&
         a.held_out == b.held_out && a.reject_quantile == b.reject_quantile &&
         a.window_m == b.window_m && a.register_centroid == b.register_centroid &&
         a.fusion == b.fusion;
}

std::vector<RenderGroup> render_groups(const SweepExperiment& e) {
  std::vector<RenderGroup> groups;
  for (std::size_t i = 0; i < e.conditions.size(); ++i) {
    const SweepCondition& c = e.conditions[i];
    auto g = std::find_if(groups.begin(), groups.end(), [&](const RenderGroup& x) {
      return x.altitude_min_m == c.altitude_min_m && x.altitude_max_m == c.altitude_max_m &&
             x.source_level_offset_db == c.source_level_offset_db &&
             x.burial_fraction == c.burial_fraction;
    });
    if (g == groups.end()) {
      groups.push_back(RenderGroup{c.altitude_min_m,
                                   c.altitude_max_m,
                                   c.source_level_offset_db,
                                   c.burial_fraction,
                                   {},
                                   {},
                                   0,
                                   1});
      g = groups.end() - 1;
    }
    auto r = std::find(g->resolutions_m.begin(), g->resolutions_m.end(), c.resolution_m);
    if (r == g->resolutions_m.end()) {
      g->resolutions_m.push_back(c.resolution_m);
      g->members.emplace_back();
      r = g->resolutions_m.end() - 1;
    }
    g->members[static_cast<std::size_t>(r - g->resolutions_m.begin())].push_back(i);
    g->train_count = std::max(g->train_count, c.train_count);
    g->looks = std::max(g->looks, c.looks);
  }
  return groups;
}

render::ChipDatasetSpec render_group_spec(const SweepExperiment& e, const RenderGroup& g,
                                          const SweepSettings& s, bool test, int look) {
  if (s.seabeds.empty()) throw std::invalid_argument("sweep: no seabed kinds");
  if (look < 0 || look >= g.looks || (!test && look != 0)) {
    throw std::invalid_argument("sweep: look " + std::to_string(look) + " of a group with " +
                                std::to_string(g.looks) + " (training chips: look 0 only)");
  }
  render::ChipDatasetSpec spec;
  spec.seed = test ? s.seed + kTestSeedOffset : s.seed;
  spec.kind = e.kind;
  spec.classes = e.classes;
  spec.seabeds = s.seabeds;
  spec.resolutions_m = g.resolutions_m;
  spec.altitude_min_m = g.altitude_min_m;
  spec.altitude_max_m = g.altitude_max_m;
  spec.sonar = s.sonar;
  spec.sonar.source_level_db += g.source_level_offset_db;
  spec.burial_fraction = test ? g.burial_fraction : 0.0;
  spec.renderer = s.renderer;
  spec.look = look;
  spec.look_geometry = s.look_geometry;
  return spec;
}

std::map<std::string, atr::ClassMetadata, std::less<>> target_class_metadata() {
  std::map<std::string, atr::ClassMetadata, std::less<>> out;
  for (const auto& t : targets::target_type_table())
    out[std::string(t.key)] = {t.mine_like, t.size_m.z()};
  return out;
}

std::vector<ChipSet> group_chip_sets(const SweepExperiment& e, const RenderGroup& g,
                                     const SweepSettings& s) {
  const std::size_t classes = e.classes.size();
  const std::size_t n_train = static_cast<std::size_t>(g.train_count) * classes;
  const std::size_t n_test = static_cast<std::size_t>(e.test_count) * classes;
  std::vector<ChipSet> out;
  const auto add = [&](ChipSetRole role, int look, const render::ChipDatasetSpec& spec,
                       std::size_t count) {
    out.push_back({role, look, std::make_unique<render::ChipRenderer>(spec), count});
  };
  if (is_fusion(e)) {
    const auto [train_highlight, train_shadow] = fusion_specs(e, g, s, false);
    const auto [test_highlight, test_shadow] = fusion_specs(e, g, s, true);
    add(ChipSetRole::kTrain, 0, train_highlight, n_train);
    add(ChipSetRole::kTrainShadow, 0, train_shadow, n_train);
    add(ChipSetRole::kTest, 0, test_highlight, n_test);
    add(ChipSetRole::kTestShadow, 0, test_shadow, n_test);
    return out;
  }
  add(ChipSetRole::kTrain, 0, render_group_spec(e, g, s, false), n_train);
  for (int look = 0; look < g.looks; ++look)
    add(ChipSetRole::kTest, look, render_group_spec(e, g, s, true, look), n_test);
  return out;
}

std::pair<render::ChipDatasetSpec, render::ChipDatasetSpec> fusion_specs(const SweepExperiment& e,
                                                                         const RenderGroup& g,
                                                                         const SweepSettings& s,
                                                                         bool test) {
  render::ChipDatasetSpec highlight = render_group_spec(e, g, s, test);
  highlight.kind = chips::ChipKind::kHighlight;
  // the shadow chips' range for both, so that chip i is the same object in both datasets
  // (chip_params draws every parameter for either kind)
  highlight.range_min_m = chips::kShadowGroundRange_m;
  highlight.range_max_m = chips::kShadowGroundRange_m;
  render::ChipDatasetSpec shadow = highlight;
  shadow.kind = chips::ChipKind::kShadow;
  return {highlight, shadow};
}

std::vector<LabelledChip> training_prefix(const std::vector<LabelledChip>& chips, int count,
                                          std::size_t classes) {
  const std::size_t n =
      std::min(chips.size(), static_cast<std::size_t>(std::max(count, 0)) * classes);
  return {chips.begin(), chips.begin() + static_cast<std::ptrdiff_t>(n)};
}

std::vector<LabelledChip> training_set(const std::vector<LabelledChip>& chips,
                                       const SweepExperiment& e, const SweepCondition& c) {
  std::vector<LabelledChip> out = training_prefix(chips, c.train_count, e.classes.size());
  std::vector<std::string> untrained;  // the held-out class and the novel ones
  for (std::size_t k = 0; k < e.classes.size(); ++k) {
    if (static_cast<int>(k) == c.held_out || k >= e.novel_from)
      untrained.emplace_back(targets::target_type_info(e.classes[k]).key);
  }
  std::erase_if(out, [&](const LabelledChip& l) {
    return std::find(untrained.begin(), untrained.end(), l.label) != untrained.end();
  });
  return out;
}

}  // namespace sonarloop::study
