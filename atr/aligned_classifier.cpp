#include "atr/aligned_classifier.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace sonarloop::atr {

AlignedClassifier::AlignedClassifier(Classifier& classifier, const AlignmentSearch& search)
    : classifier_(classifier), search_(search) {
  if (search.rows < 0 || search.cols < 0 || search.coarse_step < 1) {
    throw std::invalid_argument(
        "alignment search: rows and cols must be >= 0 and the coarse step >= 1");
  }
  const std::size_t classes = classifier.model().classes.size();
  best_distance_.assign(classes, 0.0f);
  best_dr_.assign(classes, 0);
  best_dc_.assign(classes, 0);
  tried_.assign(
      static_cast<std::size_t>(2 * search.rows + 1) * static_cast<std::size_t>(2 * search.cols + 1),
      0);
  const Model& m = classifier.model();
  work_.width = m.chip_width;
  work_.height = m.chip_height;
  work_.pixels.assign(m.pixel_count(), 0.0f);
  out_.result.class_distance.reserve(classes);
  out_.result.class_subspace.reserve(classes);
}

void AlignedClassifier::try_window(int dr, int dc) {
  unsigned char& tried = tried_[static_cast<std::size_t>(dr + search_.rows) *
                                    static_cast<std::size_t>(2 * search_.cols + 1) +
                                static_cast<std::size_t>(dc + search_.cols)];
  if (tried) return;
  tried = 1;
  copy_window(*context_, margin_rows_, margin_cols_, dr, dc, work_);
  const ChipCheck check = classifier_.classify(work_.view());
  ++out_.windows;
  if (dr == 0 && dc == 0) out_.check = check;
  if (!check.ok()) return;
  const Classification& r = classifier_.result();
  for (std::size_t c = 0; c < best_distance_.size(); ++c) {
    if (r.class_distance[c] < best_distance_[c]) {
      best_distance_[c] = r.class_distance[c];
      best_dr_[c] = dr;
      best_dc_[c] = dc;
    }
  }
}

const AlignedClassification& AlignedClassifier::classify(const Chip& context, int margin_rows,
                                                         int margin_cols) {
  const Model& m = classifier_.model();
  if (margin_rows < search_.rows || margin_cols < search_.cols ||
      context.width - 2 * margin_cols != m.chip_width ||
      context.height - 2 * margin_rows != m.chip_height) {
    throw std::invalid_argument(
        "aligned classifier: the context chip's margins are smaller than the alignment search, "
        "or its window is not the model's chip size");
  }
  context_ = &context;
  margin_rows_ = margin_rows;
  margin_cols_ = margin_cols;
  std::fill(best_distance_.begin(), best_distance_.end(), std::numeric_limits<float>::infinity());
  std::fill(tried_.begin(), tried_.end(), 0);
  out_.windows = 0;
  out_.dr = out_.dc = 0;
  out_.result.class_index = -1;

  // coarse grid (through 0), then the shifts around each class's best
  const int step = search_.coarse_step;
  try_window(0, 0);
  for (int dr = -(search_.rows / step) * step; dr <= search_.rows; dr += step)
    for (int dc = -(search_.cols / step) * step; dc <= search_.cols; dc += step)
      try_window(dr, dc);
  const int radius = step - 1;
  for (std::size_t c = 0; c < best_distance_.size(); ++c) {
    if (best_distance_[c] == std::numeric_limits<float>::infinity()) continue;
    const int r0 = best_dr_[c], c0 = best_dc_[c];
    for (int dr = std::max(-search_.rows, r0 - radius); dr <= std::min(search_.rows, r0 + radius);
         ++dr)
      for (int dc = std::max(-search_.cols, c0 - radius); dc <= std::min(search_.cols, c0 + radius);
           ++dc)
        try_window(dr, dc);
  }

  // the class of smallest distance over all windows
  const auto best = std::min_element(best_distance_.begin(), best_distance_.end());
  if (best == best_distance_.end() || *best == std::numeric_limits<float>::infinity()) {
    return out_;  // every window rejected: out_.check says why (the centred one)
  }
  const auto ci = static_cast<std::size_t>(best - best_distance_.begin());
  out_.dr = best_dr_[ci];
  out_.dc = best_dc_[ci];
  copy_window(context, margin_rows, margin_cols, out_.dr, out_.dc, work_);
  out_.check = classifier_.classify(work_.view());
  ++out_.windows;
  out_.result = classifier_.result();
  Classification& r = out_.result;
  r.class_index = static_cast<int>(ci);
  r.distance = best_distance_[ci];
  r.runner_up = -1;
  r.runner_up_distance = std::numeric_limits<float>::infinity();
  for (std::size_t c = 0; c < best_distance_.size(); ++c) {
    r.class_distance[c] = best_distance_[c];
    if (c != ci && best_distance_[c] < r.runner_up_distance) {
      r.runner_up = static_cast<int>(c);
      r.runner_up_distance = best_distance_[c];
    }
  }
  r.mine_like_by_identity = classifier_.model().classes[ci].mine_like;
  if (!r.by_group_subspaces) r.mine_like = r.mine_like_by_identity;
  return out_;
}

}  // namespace sonarloop::atr
