#pragma once
// Classification of a live contact whose exact centre is unknown: the eigen-subspace classifier
// (atr/subspace_classifier.h) slid over a context chip (atr/chip_cutter.h).
//
// Why. Training chips are centred on the target's true centre (sim/render/chip_renderer.h); the
// eq. 10 distance is not shift-invariant, and the detector only knows where the highlight and the
// shadow are. Measured on 400 held-out dataset chips (5 cm, 4 classes, 1600 training chips):
// 77.5 % correct when centred, 70 % shifted by one pixel, 50 % by two, 31 % by four. So each
// class is scored at its best alignment: the chip window is moved over a grid of shifts
// (|dr| <= search rows, |dc| <= search cols; coarse step first, then every shift next to each
// class's coarse best), every window is classified, and each class keeps its smallest eq. 10
// distance over all the windows. The identified class is the class of smallest distance (the
// template-matching reading of eq. 10); its window gives the object's refined centre. The cost is
// one classification per window tried (about 110 for the default search).
//
// The reported Classification is the classifier's answer at the identified class's best window,
// with class_distance, runner_up and runner_up_distance replaced by the per-class minima over all
// windows (the numbers the decision was made on). Mine / non-mine (Section 4.1.2) is the
// classifier's decision at that window.
//
// Allocation: none per contact once constructed (work chip and tables sized here).
#include <vector>

#include "atr/chip_cutter.h"
#include "atr/subspace_classifier.h"

namespace sonarloop::atr {

struct AlignmentSearch {
  int rows = 6;         // +- pixels along track (0.3 m at 5 cm)
  int cols = 10;        // +- pixels in range (0.5 m at 5 cm)
  int coarse_step = 2;  // pixels between coarse shifts (1: exhaustive)
};

struct AlignedClassification {
  ChipCheck check;        // ok, or why the centred chip was rejected
  Classification result;  // valid when check.ok()
  int dr = 0, dc = 0;     // the identified class's best window
  int windows = 0;        // windows classified
};

class AlignedClassifier {
 public:
  // `classifier` must outlive this object. Throws std::invalid_argument for a negative search.
  AlignedClassifier(Classifier& classifier, const AlignmentSearch& search);

  const AlignmentSearch& search() const { return search_; }
  // Margins a context chip needs for this search.
  int margin_rows() const { return search_.rows; }
  int margin_cols() const { return search_.cols; }

  // Classifies a context chip with the given margins (at least the search's; the window is
  // the model's chip size).
  const AlignedClassification& classify(const Chip& context, int margin_rows, int margin_cols);
  // The same for a ChipCutter's last cut.
  const AlignedClassification& classify(const ChipCutter& cutter) {
    return classify(cutter.context(), cutter.margin_rows(), cutter.margin_cols());
  }

 private:
  void try_window(int dr, int dc);

  Classifier& classifier_;
  AlignmentSearch search_;
  const Chip* context_ = nullptr;  // during classify()
  int margin_rows_ = 0, margin_cols_ = 0;
  Chip work_;
  std::vector<float> best_distance_;  // per class
  std::vector<int> best_dr_, best_dc_;
  std::vector<unsigned char> tried_;  // (2 rows + 1) x (2 cols + 1)
  AlignedClassification out_;
};

}  // namespace sonarloop::atr
