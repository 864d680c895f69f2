// sonarloop train: train the PCA (eigen-subspace) classifier on a folder of PNG or JPEG chips.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "atr/model_file.h"
#include "atr/subspace_classifier.h"
#include "mission/default_model.h"
#include "study/chip_folder.h"
#include "tools/args.h"
#include "tools/chip_options.h"
#include "tools/cli_helpers.h"
#include "tools/cmd_survey_training.h"
#include "tools/commands.h"
#include "tools/progress.h"

namespace sonarloop::tools {
namespace {

// Prints one class's (or group's) line of the summary.
void print_class(const atr::ClassModel& c, const char* kind) {
  int chips = 0;
  std::string ranks;
  for (const auto& s : c.subspaces) {
    chips += s.train_count;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s%d", ranks.empty() ? "" : " ", s.rank());
    ranks += buf;
  }
  char height[32] = "height ?";
  if (c.height_m) std::snprintf(height, sizeof height, "height %.2f m", *c.height_m);
  std::printf("  %-5s %-20s %-9s %-13s %5d chips, %zu subspace%s, rank %s", kind, c.name.c_str(),
              c.mine_like ? "mine-like" : "non-mine", height, chips, c.subspaces.size(),
              c.subspaces.size() == 1 ? "" : "s", ranks.c_str());
  if (std::isfinite(c.reject_distance))
    std::printf(", unknown beyond distance %.4g", static_cast<double>(c.reject_distance));
  std::printf("\n");
}

// A progress bar per training stage (reading chips, fitting subspaces).
struct StageProgress {
  std::string stage;
  std::unique_ptr<Progress> bar;

  void operator()(std::string_view s, std::size_t done, std::size_t total) {
    if (!bar || s != stage) {
      bar.reset();
      stage = s;
      bar = std::make_unique<Progress>(stage, static_cast<double>(total));
    }
    bar->update(static_cast<double>(done));
  }
};

// `train --default [--path]`: the default model built (if not cached yet) and its path printed;
// with --path only the path.
int run_default_train(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--default", false}, {"--path", false}});
  if (!args.positionals().empty()) {
    throw UsageError("--default takes no CHIPS_DIR ('" + args.positionals()[0] + "')");
  }
  if (args.has("--path")) {
    std::printf("%s\n", mission::default_model_path().c_str());
    return 0;
  }
  install_stop_flag();
  std::printf("%s\n",
              mission::ensure_default_model(false, [] { return stop_requested(); }).c_str());
  return 0;
}

int run_train(const std::vector<std::string>& argv) {
  for (const std::string& a : argv) {
    if (a == "--surveys" || a.rfind("--surveys=", 0) == 0) return run_survey_train(argv);
    if (a == "--default") return run_default_train(argv);
  }
  const Args args(argv, {{"--out"},
                         {"--p"},
                         {"--aspect-sectors"},
                         {"--group-subspaces", false},
                         {"--mine-like"},
                         {"--mine-classes"},
                         {"--height"},
                         {"--size"},
                         {"--skip-bad-chips", false},
                         {"--crop"},
                         {"--multilook"},
                         {"--levels"},
                         {"--fuse-levels"},
                         {"--threshold-db"},
                         {"--reject-quantile"}});
  if (args.positionals().size() != 1) throw UsageError("expected one CHIPS_DIR");
  const auto out = args.get("--out");
  if (!out) throw UsageError("--out MODEL is required");
  atr::TrainOptions opt;
  opt.p = static_cast<int>(args.get_int("--p", 1, 4096).value_or(atr::kDefaultSubspaceDim));
  opt.aspect_sectors = static_cast<int>(args.get_int("--aspect-sectors", 1, 360).value_or(1));
  opt.group_subspaces = args.has("--group-subspaces");
  opt.skip_degenerate = args.has("--skip-bad-chips");
  opt.preprocess = preprocess_options(args);
  opt.views = fused_levels_option(args, opt.preprocess);
  opt.reject_quantile = args.get_double("--reject-quantile", 0.0, 0.9999).value_or(0.0);
  const std::optional<study::ChipSize> size = chip_size_option(args);

  // list the chips; their pixels are read one at a time while training
  const auto t0 = std::chrono::steady_clock::now();
  study::ChipFolderOptions fo;
  fo.read_pixels = false;
  fo.skip_bad = opt.skip_degenerate;
  const study::ChipFolder folder = study::read_chip_folder(args.positionals()[0], fo);
  // the simulator's class metadata only for its own chips (a dataset folder has dataset.json)
  const bool simulated =
      std::filesystem::exists(std::filesystem::path(folder.root) / "dataset.json");
  opt.class_metadata = class_metadata_options(args, folder.classes, simulated);
  if (opt.aspect_sectors > 1 && folder.aspect_count < folder.chips.size()) {
    throw std::runtime_error(std::to_string(opt.aspect_sectors) +
                             " aspect sectors need an aspect angle for every "
                             "chip, but labels.csv in '" +
                             folder.root + "' gives one for " +
                             std::to_string(folder.aspect_count) + " of " +
                             std::to_string(folder.chips.size()) + " chips" +
                             (folder.has_labels_csv ? "" : " (there is no labels.csv)"));
  }
  for (const auto& s : folder.skipped)
    std::fprintf(stderr, "skipped '%s': %s\n", s.source.c_str(), s.reason.c_str());
  atr::Chip chip;
  const atr::ChipLoader load = [&](std::size_t i) {
    chip = study::read_folder_chip(folder, i, size);
    return chip.view();
  };
  StageProgress progress;
  opt.progress = std::ref(progress);
  atr::TrainReport report;
  const atr::Model model = atr::train_model(folder.chips, load, opt, &report);
  progress.bar.reset();
  const double train_s = seconds_since(t0);
  atr::save_model(model, *out);

  for (const auto& s : report.skipped)
    std::fprintf(stderr, "skipped '%s': %s\n", s.source.c_str(), s.reason.c_str());
  std::printf("trained on %zu chips of %d x %d pixels%s from '%s' (read and train %.2f s)\n",
              folder.chips.size() - report.skipped.size(), model.chip_width, model.chip_height,
              size ? " (resampled)" : "", folder.root.c_str(), train_s);
  std::printf("p = %d, %d aspect sector%s%s; pre-processing: %s (features %d x %d)\n", model.p,
              model.aspect_sectors, model.aspect_sectors == 1 ? "" : "s",
              model.groups.empty() ? "" : ", with mine / non_mine group subspaces",
              model_readings_label(model).c_str(), model.feature_width(), model.feature_height());
  for (const auto& c : model.classes)
    print_class(c, "class");
  for (const auto& g : model.groups)
    print_class(g, "group");
  if (!model.has_mine_like_class()) {
    std::printf("no class is mine-like: no mine / non-mine decision (see --mine-like)\n");
  }
  const std::size_t skipped = folder.skipped.size() + report.skipped.size();
  if (skipped) std::printf("skipped %zu bad chips (listed on stderr)\n", skipped);
  std::printf("wrote %s\n", out->c_str());
  return 0;
}

}  // namespace

const Command kTrainCommand{
    "train",
    "train the PCA (eigen-subspace) classifier on PNG or JPEG chips, one subfolder per class",
    R"(usage: sonarloop train CHIPS_DIR --out MODEL [options]
       sonarloop train --surveys SCENARIOS --out MODEL [survey options]
       sonarloop train --default [--path]

Trains the eigen-subspace classifier of Pailhas, Petillot & Capus (2010), Section 3.2: for each
class, every chip is normalised by its own mean and standard deviation (eq. 9), the class mean
image is taken (eq. 8), and the p leading eigenvectors of the centred chips are found from the
k x k Gram matrix (or the pixel covariance when a class has more chips than pixels).
Classification (sonarloop classify) picks the class whose subspace leaves the smallest residual
(eq. 10). A class with k <= p chips keeps rank k - 1.

CHIPS_DIR holds one subfolder per class, named after the class, with PNG or JPEG chips inside
(.png, .jpg, .jpeg; colour is converted to grey). All chips must have one size, or --size
resamples them. An optional CHIPS_DIR/labels.csv with columns file,class,aspect_deg,... gives
each chip's target aspect angle in degrees (file is the path relative to CHIPS_DIR, e.g.
manta/001.png). Real data works the same way as synthetic data. Chips are read one at a time:
memory holds the normalised chips once, as float (about 4 bytes a pixel), plus one class's
eigen-problem.

Class metadata, stored in the model: whether a class is mine-like (Section 4.1.2) and the height
of its objects above the seabed (`sonarloop onboard` places a contact with it). In a folder of
the simulator's chips (one `sonarloop dataset` wrote: it has dataset.json) the classes named
after a simulated target type take its values (manta, rockan, cylinder and cuboid are mine-like;
heights from the target table). Any other class, and every class of real chips even when named
like a target type, is not mine-like and of unknown height unless --mine-like and --height say
otherwise (onboard then uses the height measured from the shadow). When no class is mine-like, classify and
onboard make no mine / non-mine decision.

options:
  --out MODEL          model file to write (versioned binary, see atr/model_file.h)
  --p N                leading eigenvectors per subspace (default 20)
  --aspect-sectors N   several subspaces per class, one per aspect sector of 360/N degrees,
                       each trained on the chips of that aspect (default 1; N > 1 needs an
                       aspect_deg in labels.csv for every chip)
  --group-subspaces    also train pooled "mine" and "non_mine" subspaces for the mine / non-mine
                       decision (default: the group of the identified class)
  --mine-like A,B      the mine-like classes, comma-separated; replaces the simulator's flags
                       (--mine-like "" makes none mine-like; --mine-classes is the old name)
  --height A=H,B=H     height of each class's objects in metres (0 to 100), over the simulator's
  --size WxH           resample every chip to W x H pixels (area average) before training;
                       classify and onboard then need chips of that size (classify --size)
  --skip-bad-chips     skip bad chips instead of stopping at the first: unreadable files,
                       files that are not PNG or JPEG, nested folders, chips of another size
                       than the first, constant or non-finite chips; one line each on stderr

chip pre-processing before eq. 9 (stored in the model; classify and onboard apply it too;
default none, as the paper; measured by `sonarloop sweep --experiment ablation`):
  --crop F             keep the central fraction F of the rows and columns (e.g. 0.4 keeps
                       1.2 m of a 3 m chip: less seabed texture around the target)
  --multilook K        average the intensity over K x K pixels (odd K; speckle reduction)
  --levels L           db (default), above_seabed (only what is brighter than the chip's
                       median level), below_seabed (only what is darker), three_level
                       (+1 / 0 / -1 against the median +- --threshold-db)
  --threshold-db T     three_level threshold in dB (default 6)
  --fuse-levels L[,L]  also read every chip with these levels modes (the same crop and
                       multilook) and fuse: each class's distance is the root of its squared
                       distances summed over the readings (--levels above_seabed --fuse-levels
                       below_seabed: highlight and shadow, atr/subspace_classifier.h "Fused
                       readings"); a chip constant in a reading (no pixel below
                       the seabed) is left out of that reading's subspaces

open-set rejection (ours; default off, as the paper):
  --reject-quantile Q  calibrate, per class, the distance beyond which a chip is reported
                       unknown: the Q-quantile of the class's own chips' distances in a 5-fold
                       cross-validation over the training chips (Q = 0.95: about 5 % of a known
                       class's chips rejected); classify and onboard then report unknown

A progress bar shows on stderr when training takes more than a second.

training on surveys (--surveys; mission/survey_training.h, docs/autonomy.md): instead of a chip
folder, the model learns from what the onboard consumer sees on surveys: lock-step surveys of the
scenarios' seabeds (files, or built-in names: survey_flat, survey_ripples, survey_clutter,
survey_rocky, mission_20) with the targets drawn afresh, in two passes. Pass 1 cuts the chips of
every target the detector found (centred on the truth) and of its false alarms (a "clutter"
class: hard negatives) and trains the PCA model on them; its detections' features fit the
detection gate. Pass 2, other surveys flown with that model, fits the classification gate on
the classified detections (atr/contact_gate.h). The onboard consumer then reports only what the
gates pass. The detector flies every pass with objects from one ping up, and the model records
that rule: onboard detects as the gates were trained. Training seeds start at --seed (default
100000); missions are reported on others.
  --surveys A,B,...      the training scenarios (their seabeds; their targets are replaced)
  --surveys-per-scenario N  surveys of each per pass (default 2)
  --per-type N           targets of each class per survey (default 8)
  --classes LIST         the target types (default: the seven of Fig. 13)
  --min-separation M     between targets (default 15)
  --area-margin M        the survey area: the seabed less this (default 50)
  --max-clutter N        clutter chips kept per survey, a uniform sample (default 400)
  --false-per-target B   the classification gate's budget: at most B false detections per
                         target on each training seabed (default 0.1) ...
  --keep-targets F       ... where that keeps at least this fraction of the seabed's targets
                         that reach the gate, a target when one of its detections passes
                         (default 0.97); a seabed that cannot have both keeps F of its targets
                         (mission/survey_training.h, choose_gate_threshold; the detection gate
                         keeps 0.99, or F if larger, where that costs at most 10 false
                         detections per target)
  --p N, --aspect-sectors N  as above (defaults 10 and 8)
  --levels L, --fuse-levels L[,L]  as above (defaults above_seabed and below_seabed: the
                         highlight and the shadow fused; --fuse-levels none for one reading,
                         as is --levels below_seabed alone)
  --crop F               as above (default 0.4: the chip's central 1.2 m)
  --gate-rows PREFIX     also write each gate's training rows (features, label, target) to
                         PREFIX_detection.csv and PREFIX_classification.csv
  --seed S, --threads N
The default model of `sonarloop mission` is this with its defaults on the five built-in
scenarios (mission/default_model.h): about 6 minutes on 2 cores, cached. `train --default`
builds it now (if it is not cached yet) and prints its path; `--path` prints the path only.

examples:
  sonarloop train out/chips --out out/atr.slpca
  sonarloop train out/chips --out out/atr8.slpca --aspect-sectors 8 --p 10
  sonarloop train out/chips --out out/atr_crop.slpca --crop 0.4 --reject-quantile 0.95
  sonarloop train ~/survey/chips --out survey.slpca --size 64x64 --skip-bad-chips \
      --mine-like mine,torpedo --height mine=0.5,torpedo=0.53,rock=0.8
  sonarloop train --surveys survey_flat,survey_clutter,survey_rocky --out out/surveys.slpca
)",
    run_train, 60};
SONARLOOP_REGISTER_COMMAND(kTrainCommand);

}  // namespace sonarloop::tools
