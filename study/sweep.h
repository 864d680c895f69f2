#pragma once
// The resolution study of Pailhas, Petillot & Capus, "High-Resolution Sonars: What Resolution Do
// We Need for Target Recognition?", EURASIP J. Adv. Signal Process. 2010, Sections 3-4, as
// experiments run in memory: chips from sim/render/chip_renderer.h, the eigen-subspace
// classifier of atr/subspace_classifier.h, scored with atr/confusion.h.
//
// An experiment is a list of conditions (points on a curve): what to render (pixel size R,
// altitude range, source level) and how to train (chips per class, p, aspect sectors). Training
// chips come from the dataset of seed S, test chips from the dataset of seed S + 1 (other
// targets, seabeds, geometries, speckle), so a model never sees its test chips. Chip i of a
// dataset is the same target at every resolution (chip_renderer.h), so curves against R
// compare like with like. Conditions with the same rendering share their chips: the training
// set of a smaller train count is a prefix of the larger one (chips alternate over the classes,
// so every prefix of k x classes chips holds k per class).
//
// The experiments (names for --experiment):
//   fig11       Fig. 11: Manta, Rockan, cuboid, cylinder from highlights, 15 resolutions
//               3-30 cm; misidentification per target against R.
//   fig13       Fig. 13 (Sec. 4.1.2): mine-like Manta, Rockan, cylinder and the four non-mine
//               shapes (cuboid 100 x 50 x 40 cm, hemispheres of 100 and 50 cm, box 70 x 70 x 40
//               cm); identification among the seven, then the mine / non-mine decision error.
//   fig15       Fig. 15: the four targets from their shadows (ChipKind::kShadow), 5-30 cm.
//               With SweepSettings::looks = N > 1, fig11, fig13 and fig15 see each test object
//               in N looks and draw one curve per number of looks fused (SweepCondition::looks).
//   aspect      error against the target's aspect, one subspace per target against several
//               subspaces per target, each for an aspect sector (the paper's remedy).
//   snr         stability: source level lowered step by step (the thermal noise stays, so the
//               signal-to-noise ratio falls by the same number of dB), at 5 cm.
//   altitude    stability: fixed sonar altitudes 2-20 m (grazing angle), at 5 cm.
//   train_size  stability: training chips per class 5-320, at 5 cm.
//   p           stability and speed: subspace dimension p 1-80, at 5 cm.
//   open_set    open-set rejection on the seven targets of fig13: each type in turn is left out
//               of training, and its test chips should be rejected as unknown; then the novel
//               types (SweepSettings::novel), never trained; the known types' false-reject
//               rate (5 and 15 cm).
//   burial      stability: test targets buried by 0-50 % of their height (trained on proud
//               ones), fig13's seven with the mine / non-mine decision, at 5 cm.
//   fusion      highlight + shadow fusion (atr/fusion.h): the same objects (the four targets at
//               25 m ground range) identified from their highlight chip, their shadow chip, and
//               both (5-20 cm).
//   fusion13    the same with fig13's seven and the mine / non-mine decision.
//   registration the four targets' highlights in a 1.2 m window cut 0-0.5 m off the target, as
//               cut and re-centred on the highlight centroid (atr/chip_register.h), at 5 cm.
//   ablation    the chip pre-processing factors of atr/chip_preprocess.h (crop, multilook,
//               levels against the seabed), one at a time and combined, at 5 and 15 cm, on
//               the four targets' highlights; every experiment also scores each test seabed.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "atr/chip.h"
#include "atr/chip_preprocess.h"
#include "atr/confusion.h"
#include "atr/fusion.h"
#include "atr/subspace_classifier.h"
#include "sim/render/chip_renderer.h"

namespace sonarloop::study {

// Seed offset of the test dataset against the training dataset.
inline constexpr std::uint64_t kTestSeedOffset = 1;
// Aspect bins of the aspect experiment (30 deg each).
inline constexpr int kSweepAspectBins = 12;

// An error count with its rate and 95 % Wilson interval (confusion.h).
struct ErrorRate {
  std::size_t n = 0;
  std::size_t errors = 0;
  double rate = 0.0;  // errors / n (0 when n = 0)
  atr::Interval ci;   // of the error rate
};
ErrorRate error_rate(std::size_t errors, std::size_t n, double z = atr::kZ95);

// A rendered chip as the classifier sees it: pixels 0..255 as float; with deripple, the sand
// ripples' periodic texture notched out (atr/chip_deripple.h); then with shadow_height, a
// shadow chip resampled to height coordinates (atr/shadow_height.h) with the geometry the chip
// was rendered with.
atr::Chip classifier_chip(const render::ChipImage& c, bool shadow_height = false,
                          bool deripple = false);
// The same with its label (the target's key) and aspect, for training.
atr::LabelledChip labelled_chip(const render::ChipImage& c, bool shadow_height = false,
                                bool deripple = false);

// What the command line sets.
struct SweepSettings {
  std::uint64_t seed = 0;
  int train_count = 80;  // per class and condition (the paper: 80)
  int test_count = 100;  // per class and condition (the paper: 10,000)
  int p = atr::kDefaultSubspaceDim;
  int aspect_sectors = 1;              // subspaces per target (the aspect experiment sets its own)
  std::vector<double> resolutions_cm;  // empty: each experiment's own list
  // fig13's non-mine shapes (sim/targets/target_type.h); default: the paper's four
  std::vector<targets::TargetType> non_mine = {
      targets::TargetType::kLargeCuboid, targets::TargetType::kHemisphere,
      targets::TargetType::kSmallHemisphere, targets::TargetType::kBox};
  // open_set's novel types: rendered and tested, never trained (default: the standing
  // cylinder, unlike all of fig13's seven); empty: none
  std::vector<targets::TargetType> novel = {targets::TargetType::kStandingCylinder};
  std::vector<render::DatasetSeabed> seabeds;  // must not be empty
  render::SonarDesc sonar;
  render::RendererKind renderer = render::RendererKind::kProfile;
  // every condition's chip pre-processing (the ablation sets its own); default none, as the paper
  atr::ChipPreprocess preprocess;
  // highlight experiments crop each resolution's chips by adaptive_crop_fraction (overrides
  // preprocess.crop_fraction; not the ablation, not shadow chips)
  bool crop_auto = false;
  // shadow chips (fig15, fusion) resampled to height coordinates before anything else
  // (atr/shadow_height.h; ours, off by default as the paper)
  bool shadow_height = false;
  // every chip's periodic sand-ripple texture notched out first (atr/chip_deripple.h; ours, off
  // by default as the paper)
  bool deripple = false;
  double reject_quantile = 0.95;  // open_set's calibration quantile
  // fig11, fig13, fig15: each test object seen in up to this many looks (passes), and one
  // curve per number of looks fused, 1 to looks (SweepCondition::looks); 1: the paper's single
  // chip. The other experiments score single chips whatever this is.
  int looks = 1;
  // how those looks are flown (render::ChipDatasetSpec::look_geometry)
  render::LookGeometry look_geometry = render::LookGeometry::kIndependent;
};

// The most looks a sweep fuses (SweepSettings::looks).
inline constexpr int kMaxSweepLooks = 8;

// Which chips of an object a fusion condition scores.
enum class FusionInput { kNone, kHighlight, kShadow, kFused };

// One point of an experiment.
struct SweepCondition {
  std::string series;  // curve label, e.g. "8 sectors"; "" for the single curve
  std::string x_name;  // "resolution_cm", "p", "train_per_class", "source_level_db", ...
  double x = 0.0;
  // rendering: conditions with equal values share chips
  double resolution_m = 0.05;
  double altitude_min_m = 2.0;
  double altitude_max_m = 10.0;
  double source_level_offset_db = 0.0;
  double burial_fraction = 0.0;  // of the TEST targets' height; training targets lie proud
  // training
  int train_count = 80;  // per class
  int p = atr::kDefaultSubspaceDim;
  int aspect_sectors = 1;
  atr::ChipPreprocess preprocess;  // the model's pre-processing (TrainOptions::preprocess)
  // open-set rejection: a class left out of training (index into the experiment's classes,
  // -1 none) and the calibration quantile (TrainOptions::reject_quantile, 0 off)
  int held_out = -1;
  double reject_quantile = 0.0;
  // registration (the registration experiment; atr/chip_register.h): chips cut as a window of
  // window_m a side (0: off) around the chip's centre, test chips around a point
  // misregister_m off it at most (uniform in a disc, drawn from the chip's index), and with
  // register_centroid re-centred on the highlight centroid found in a cue window
  // kRegistrationCueMargin_m larger
  double window_m = 0.0;
  double misregister_m = 0.0;
  bool register_centroid = false;
  FusionInput fusion = FusionInput::kNone;  // the fusion experiment's conditions
  atr::FusionNorm fusion_norm = atr::FusionNorm::kModelTypical;
  // multi-look fusion (ours): each test object is identified from looks 0 .. looks-1 of the
  // test dataset (render::ChipDatasetSpec::look: the same object from other passes), by the
  // smallest sum of its looks' eq. 10 distances (atr/fusion.h; one model, so one scale);
  // 1: from its chip alone, as the paper
  int looks = 1;
};

// Whether two conditions of one rendering train the same model from the same chips (they differ
// only in how the test chips are scored, e.g. the looks fused), so that one model serves both.
bool same_training(const SweepCondition& a, const SweepCondition& b);

// The registration experiment's cue window is this much larger than the chip window (m): a
// detector's window that still holds the target when its position is off by half of it.
inline constexpr double kRegistrationCueMargin_m = 0.8;

// The chip a registration condition classifies (SweepCondition::window_m > 0): a window cut
// from the rendered chip around its centre (training, test = false) or around a misregistered
// point (test), optionally re-centred on the highlight centroid. `index` draws the offset.
atr::Chip registration_chip(atr::ChipView chip, const SweepCondition& c, std::uint64_t index,
                            bool test);

struct SweepExperiment {
  std::string name;
  std::string title;
  chips::ChipKind kind = chips::ChipKind::kHighlight;
  std::vector<targets::TargetType> classes;
  bool mine_groups = false;               // also score the mine / non-mine decision
  int aspect_bins = 0;                    // > 0: also score per aspect bin
  int test_count = 100;                   // per class
  std::vector<std::string> seabed_names;  // the dataset's seabeds (ChipParams::seabed)
  std::vector<SweepCondition> conditions;
  // classes from this index on are never trained (open_set's novel types): a condition that
  // holds one of them out tests it as unknown, the others skip their chips
  std::size_t novel_from = static_cast<std::size_t>(-1);
};

// Sec. 4.1.2: the mine-like Manta, Rockan and cylinder, then settings.non_mine.
std::vector<targets::TargetType> fig13_classes(const SweepSettings& settings);

std::vector<std::string> sweep_experiment_names();
// fusion and fusion13: a highlight and a shadow chip per object (FusionInput conditions)
bool is_fusion(const SweepExperiment& e);
// Throws std::invalid_argument naming the allowed experiments for an unknown name.
SweepExperiment make_sweep_experiment(const std::string& name, const SweepSettings& settings);

// Conditions that share rendered chips: same altitude range, source level and burial (one
// renderer, all their resolutions), then the same resolution.
struct RenderGroup {
  double altitude_min_m = 0.0;
  double altitude_max_m = 0.0;
  double source_level_offset_db = 0.0;
  double burial_fraction = 0.0;
  std::vector<double> resolutions_m;              // distinct, in order of first use
  std::vector<std::vector<std::size_t>> members;  // (resolutions) condition indices
  int train_count = 0;                            // the largest of its conditions, per class
  int looks = 1;  // test looks rendered per object: the most any of its conditions fuses
};
std::vector<RenderGroup> render_groups(const SweepExperiment& e);

// The dataset of a render group: training (test = false, seed S; targets never buried; look 0)
// or test (seed S + 1) seen in look `look` (0 .. g.looks - 1).
render::ChipDatasetSpec render_group_spec(const SweepExperiment& e, const RenderGroup& g,
                                          const SweepSettings& settings, bool test, int look = 0);

// The fusion experiment's two datasets of a render group: highlight chips (test = false: seed
// S) and shadow chips of the same objects, all at the shadow chips' 25 m ground range.
std::pair<render::ChipDatasetSpec, render::ChipDatasetSpec> fusion_specs(
    const SweepExperiment& e, const RenderGroup& g, const SweepSettings& settings, bool test);

// What a chip set of a render group holds (ChipSet::role).
enum class ChipSetRole : std::uint8_t {
  kTrain,        // training chips (fusion: the highlight chips)
  kTrainShadow,  // fusion: the training objects' shadow chips
  kTest,         // test chips of one look (fusion: the highlight chips)
  kTestShadow,   // fusion: the test objects' shadow chips
};
// One set of chips a render group renders at each of its resolution slots.
struct ChipSet {
  ChipSetRole role = ChipSetRole::kTrain;
  int look = 0;  // kTest: the look (0 .. g.looks - 1)
  std::unique_ptr<render::ChipRenderer> renderer;
  std::size_t count = 0;  // chips per slot (per class count x classes)
};
// A render group's chip sets in the one order in which they are rendered at each resolution
// slot, by rank 0 of a sweep and by the ranks serving it (MPI: every rank makes the same render
// calls in the same order): fusion: training highlight, training shadow, test highlight, test
// shadow; otherwise: training, test, then the test objects' other looks, 1 .. g.looks - 1.
std::vector<ChipSet> group_chip_sets(const SweepExperiment& e, const RenderGroup& g,
                                     const SweepSettings& settings);

// The class metadata of the simulator's target types (their mine-like flag and height), for
// the models the study trains on them.
std::map<std::string, atr::ClassMetadata, std::less<>> target_class_metadata();

// A training set: the first count x classes chips of `chips` (count per class).
std::vector<atr::LabelledChip> training_prefix(const std::vector<atr::LabelledChip>& chips,
                                               int count, std::size_t classes);
// A condition's training set: its prefix, without the held-out class's chips.
std::vector<atr::LabelledChip> training_set(const std::vector<atr::LabelledChip>& chips,
                                            const SweepExperiment& e, const SweepCondition& c);

// The scores of one condition.
struct ConditionResult {
  std::size_t condition = 0;
  atr::ConfusionMatrix confusion;
  std::size_t mine_n = 0, mine_errors = 0;
  std::vector<std::size_t> aspect_n, aspect_errors;  // (classes x aspect bins), row-major
  std::vector<std::size_t> seabed_n, seabed_errors;  // (seabeds) identification per test seabed
  // (classes x seabeds), row-major: identification per target and test seabed
  std::vector<std::size_t> class_seabed_n, class_seabed_errors;
  // open-set rejection: known-class chips called unknown; held-out-class chips not called unknown
  std::size_t known_n = 0, known_rejected = 0;
  std::size_t unknown_n = 0, unknown_accepted = 0;
  std::size_t rejected = 0;  // degenerate test chips
  // timings, filled by the caller: thread-seconds to render one chip, seconds to train the
  // model, seconds to classify one chip (one thread)
  double render_s_per_chip = 0.0;
  double train_s = 0.0;
  double classify_s_per_chip = 0.0;
  bool complete = false;  // every test chip was scored (false after Ctrl-C)

  ConditionResult(std::size_t index, const SweepExperiment& e, const atr::Model& m);
};

// Scores one test chip: `truth` indexes e.classes, `seabed` e.seabed_names; r is the
// classifier's answer.
void score_chip(ConditionResult& out, const SweepExperiment& e, const atr::Model& m,
                std::size_t truth, double aspect_deg, int seabed, const atr::Classification& r);

// CSV files (header line included). Rates in percent.
//   results: experiment,series,x_name,x,resolution_cm,class,n,errors,error_pct,ci_low_pct,
//            ci_high_pct,train_per_class,p,aspect_sectors,render_ms_per_chip,train_s,
//            classify_ms_per_chip,complete
//   with class = a target key, "all" (identification over all classes), "mine_vs_non_mine",
//   "seabed_NAME" (identification over the test chips on that seabed, when there are
//   several), "false_reject" (known-class chips called unknown) or "unknown_accepted"
//   (held-out chips not called unknown); with open-set rejection a known chip called unknown is
//   a misidentification, and held-out chips are left out of the per-class rows and "all";
//   the aspect experiment adds rows with x_name = "aspect_deg" (bin centre) per series.
std::string results_csv(const SweepExperiment& e, const std::vector<ConditionResult>& results);
//   confusion: experiment,series,x_name,x,truth,predicted,count
std::string confusion_csv(const SweepExperiment& e, const std::vector<ConditionResult>& results);
//   seabed: experiment,series,x_name,x,resolution_cm,class,seabed,n,errors,error_pct,ci_low_pct,
//           ci_high_pct: each target's identification on each test seabed (where a target's
//           errors lie: the results' seabed_NAME rows pool the targets); the header alone when
//           the experiment has one seabed
std::string seabed_csv(const SweepExperiment& e, const std::vector<ConditionResult>& results);

}  // namespace sonarloop::study
