#pragma once
// `sonarloop classify`'s scoring and reports (tools/cmd_classify.cpp classifies; this scores and
// writes): each chip's line on stdout, the scores against the truth of a labelled folder
// (confusion matrix, accuracy and mine / non-mine accuracy with 95 % Wilson intervals, accuracy by
// true aspect), the --csv rows and the --json document.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "atr/confusion.h"
#include "atr/model_file.h"
#include "atr/subspace_classifier.h"
#include "study/chip_folder.h"

namespace sonarloop::study {

// One chip's outcome.
struct ClassifiedChip {
  const atr::LabelledChip* chip = nullptr;
  atr::ChipCheck check;
  atr::Classification result;  // valid when check.ok()
};

// The counts of one classify run.
struct ClassifyCounts {
  std::size_t classified = 0;
  std::size_t rejected = 0;  // degenerate chips (ChipCheck not ok)
  std::size_t skipped = 0;   // unreadable files
  double per_chip_us = 0.0;  // classifier time per classified chip
};

// The scores against the truth (a labelled folder with at least one chip classified).
struct ClassifyScores {
  struct AspectBin {
    std::size_t total = 0, correct = 0;
  };
  std::optional<atr::ConfusionMatrix> confusion;  // empty: nothing to score
  std::size_t mine_total = 0, mine_correct = 0;   // chips whose truth's mine-likeness is known
  int aspect_bins = 0;
  std::vector<AspectBin> bins;  // by true aspect; empty when off or no aspect is known
};

// Scores the classified chips of a labelled folder against their labels (empty scores otherwise).
ClassifyScores score_chips(const atr::Model& m, const study::ChipFolder& folder,
                           const std::vector<ClassifiedChip>& rows, std::size_t classified,
                           int aspect_bins);

// One line per classified chip on stdout (unless quiet), and each rejected chip's reason on stderr.
void print_chip_lines(const atr::Model& m, const std::vector<ClassifiedChip>& rows, bool quiet);
// The counts, then the scores when there are any.
void print_summary(const atr::Model& m, const std::string& model_path, const ClassifyCounts& n);
void print_scores(const ClassifyScores& s);

// --csv: one row per chip. Throws std::runtime_error when the file cannot be written.
void write_classify_csv(const std::string& path, const atr::Model& m,
                        const std::vector<ClassifiedChip>& rows);
// --json: the chips and the summary. Throws std::runtime_error when the file cannot be written.
void write_classify_json(const std::string& path, const atr::Model& m,
                         const std::string& model_path, const study::ChipFolder& folder,
                         const std::vector<ClassifiedChip>& rows, const ClassifyCounts& n,
                         const ClassifyScores& s);

}  // namespace sonarloop::study
