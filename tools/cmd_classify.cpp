// sonarloop classify: classify PNG or JPEG chips with a trained PCA model; score against the truth
// when the chips come in class subfolders.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "atr/confusion.h"
#include "atr/model_file.h"
#include "atr/subspace_classifier.h"
#include "study/chip_folder.h"
#include "study/classify_report.h"
#include "tools/args.h"
#include "tools/chip_options.h"
#include "tools/commands.h"
#include "tools/progress.h"

namespace sonarloop::tools {
using study::ClassifiedChip;
using study::ClassifyCounts;
using study::ClassifyScores;
using study::print_chip_lines;
using study::print_scores;
using study::print_summary;
using study::score_chips;
using study::write_classify_csv;
using study::write_classify_json;
namespace {

// The chips of a folder (labelled when it has class subfolders), listed without their pixels;
// or one image file, read.
study::ChipFolder list_input(const std::string& input, bool skip_bad,
                             const std::optional<study::ChipSize>& size) {
  study::ChipFolder folder;
  if (std::filesystem::is_directory(input)) {
    study::ChipFolderOptions fo;
    fo.require_classes = false;
    fo.require_same_size = false;  // the classifier rejects each chip of the wrong size
    fo.read_pixels = false;
    fo.skip_bad = skip_bad;
    folder = study::read_chip_folder(input, fo);
  } else {
    folder.root = input;
    folder.chips.push_back(study::read_chip_file(input, size));
  }
  return folder;
}

// The classification of every chip (read, resample, classify), timing the classifier alone.
// Unreadable chips are skipped (counted) with --skip-bad-chips, else stop the command.
std::vector<ClassifiedChip> classify_chips(atr::Classifier& clf, study::ChipFolder& folder,
                                           const std::optional<study::ChipSize>& size,
                                           bool one_file, bool skip_bad, ClassifyCounts& n) {
  std::vector<ClassifiedChip> rows;
  rows.reserve(folder.chips.size());
  double classify_s = 0.0;
  std::size_t classified = 0, unreadable = 0;
  Progress bar("classifying " + std::to_string(folder.chips.size()) + " chips",
               static_cast<double>(folder.chips.size()));
  for (std::size_t i = 0; i < folder.chips.size(); ++i) {
    bar.update(static_cast<double>(i));
    atr::Chip chip;
    try {
      chip = one_file ? std::move(folder.chips[i].chip) : study::read_folder_chip(folder, i, size);
    } catch (const std::runtime_error& e) {
      if (!skip_bad) throw;
      std::fprintf(stderr, "skipped '%s': %s\n", folder.chips[i].source.c_str(), e.what());
      ++unreadable;
      continue;
    }
    ClassifiedChip& row = rows.emplace_back();
    row.chip = &folder.chips[i];
    const auto t = std::chrono::steady_clock::now();
    row.check = clf.classify(chip.view());
    classify_s += seconds_since(t);
    if (row.check.ok()) {
      row.result = clf.result();
      ++classified;
    }
  }
  bar.finish();
  n.classified = classified;
  n.rejected = rows.size() - classified;
  n.skipped = folder.skipped.size() + unreadable;
  n.per_chip_us = classified ? 1e6 * classify_s / static_cast<double>(classified) : 0.0;
  return rows;
}

int run_classify(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--csv"},
                         {"--json"},
                         {"--quiet", false},
                         {"--aspect-bins"},
                         {"--size"},
                         {"--skip-bad-chips", false}});
  if (args.positionals().size() != 2) throw UsageError("expected MODEL and CHIPS_DIR or CHIP.png");
  const int aspect_bins = static_cast<int>(args.get_int("--aspect-bins", 0, 360).value_or(12));
  const bool quiet = args.has("--quiet");
  const bool skip_bad = args.has("--skip-bad-chips");
  const std::string& model_path = args.positionals()[0];
  const std::string& input = args.positionals()[1];

  atr::Classifier clf(load_model_with_metadata(model_path));
  const atr::Model& m = clf.model();
  // chips of another size than the model's are resampled to it (area average), as `train
  // --size` resampled the training chips; --size chooses another size
  std::optional<study::ChipSize> size = chip_size_option(args);
  if (!size) size = study::ChipSize{m.chip_width, m.chip_height};
  const bool one_file = !std::filesystem::is_directory(input);
  study::ChipFolder folder = list_input(input, skip_bad, size);
  for (const auto& s : folder.skipped)
    std::fprintf(stderr, "skipped '%s': %s\n", s.source.c_str(), s.reason.c_str());

  ClassifyCounts n;
  const std::vector<ClassifiedChip> rows = classify_chips(clf, folder, size, one_file, skip_bad, n);
  print_chip_lines(m, rows, quiet);
  print_summary(m, model_path, n);
  const ClassifyScores scores = score_chips(m, folder, rows, n.classified, aspect_bins);
  print_scores(scores);
  if (const auto csv = args.get("--csv")) write_classify_csv(*csv, m, rows);
  if (const auto json_path = args.get("--json")) {
    write_classify_json(*json_path, m, model_path, folder, rows, n, scores);
  }
  if (!n.classified) {
    throw std::runtime_error("no chip could be classified (" + std::to_string(n.rejected) +
                             " rejected, reasons above)");
  }
  return 0;
}

}  // namespace

const Command kClassifyCommand{
    "classify",
    "classify PNG or JPEG chips with a trained model; confusion matrix and accuracy if labelled",
    R"(usage: sonarloop classify MODEL CHIPS_DIR|CHIP.png|CHIP.jpg [options]

Classifies each chip with the eigen-subspace model written by 'sonarloop train': the chip is
normalised by its own mean and standard deviation and given the class whose subspace leaves the
smallest residual (Pailhas, Petillot & Capus 2010, eq. 10); the mine / non-mine decision
(Section 4.1.2) follows when the model has a mine-like class (see train --mine-like; without
one, no mine / non-mine column or score is printed). Prints one line per chip: file, predicted
class and distance, the runner-up, mine / non-mine, and the truth when known.

CHIPS_DIR is either a folder with one subfolder per class (as for 'sonarloop train': the truth
is the subfolder), or a folder of PNG or JPEG chips without classes. With class subfolders the
command also prints the confusion matrix, the accuracy with its 95 % Wilson score interval, the
mine / non-mine accuracy, and, when CHIPS_DIR/labels.csv gives aspect_deg, the accuracy by true
aspect angle. A class the model does not know always counts as wrong. Chips are read one at a
time (a progress bar shows on stderr after a second).

Degenerate chips (constant, non-finite, of another size than the model's) are rejected with a
reason on stderr and left out of the scores. Files that are not PNG or JPEG, unreadable images
and nested folders stop the command, unless --skip-bad-chips. The exit status is 0 when at
least one chip was classified, 1 otherwise or on error, 2 on a usage error.

options:
  --csv FILE          one row per chip: predictions, distances to every class, reasons
  --json FILE         per-chip predictions and the summary (confusion matrix, accuracy, CIs)
  --quiet             no per-chip lines (rejections and the summary only)
  --aspect-bins N     bins for the accuracy by aspect (default 12, 0 = off)
  --size WxH          resample every chip to W x H pixels (area average) first (default:
                      the model's chip size, so that chips cut at another size are
                      resampled as `train --size` resampled the training chips)
  --skip-bad-chips    skip unreadable files, non-images and nested folders, one line each on
                      stderr, instead of stopping at the first

examples:
  sonarloop classify out/atr.slpca out/test_chips
  sonarloop classify out/atr.slpca out/test_chips --quiet --json out/scores.json
  sonarloop classify out/atr.slpca contact_0042.png
  sonarloop classify survey.slpca ~/survey/test_chips --size 64x64 --skip-bad-chips
)",
    run_classify, 61};
SONARLOOP_REGISTER_COMMAND(kClassifyCommand);

}  // namespace sonarloop::tools
