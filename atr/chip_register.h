#pragma once
// Registration of highlight chips (ours; the "registration" factor of the chip pre-processing
// ablation, docs/sweep.md). A chip cut around a detector's contact is off the target's centre by
// the detector's position error, while the subspaces were trained on chips centred on it.
// Registration re-centres the chip on something the image itself shows: here the intensity
// centroid of its brightest pixels, the highlight (a target's echo is the brightest thing in a
// chip of seabed). Training chips registered the same way keep train and test alike.
//
// Pure functions on chip views: the same chip gives the same bytes.
#include "atr/chip.h"

namespace sonarloop::atr {

// A position in a chip, in pixels (row down, column right; pixel centres at integers).
struct ChipPoint {
  double row = 0.0;
  double col = 0.0;
};

// The centroid of the pixels above the chip's q-quantile level (about the brightest 1 - q of
// them), each weighted by how far above that level it is (so that the many pixels of an 8-bit
// chip tied at the level weigh nothing); the plain centroid of the pixels at the level when none
// exceeds it. q in [0, 1). Throws std::invalid_argument for an empty chip or q outside [0, 1).
ChipPoint highlight_centroid(ChipView chip, double quantile = 0.99);

// The `width` x `height` window of `chip` centred on `centre` (its pixel (i, j) is the chip's
// pixel nearest to centre + (i - (height - 1)/2, j - (width - 1)/2)); pixels outside the chip
// take the chip's median level (the seabed). Throws std::invalid_argument for an empty chip or
// a window size below 1.
Chip chip_window(ChipView chip, int width, int height, ChipPoint centre);

}  // namespace sonarloop::atr
