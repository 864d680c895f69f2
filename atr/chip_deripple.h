#pragma once
// Sand-ripple texture suppression: a notch filter on the chip's 2-D spectrum (ours; a chip
// pre-processing step the paper does not have, issue 9's "ripple-texture suppression").
//
// Sand ripples are a quasi-periodic relief: crests along one direction, repeating every
// wavelength λ (0.8 m on the chip renderer's rippled seabed). In a sidescan image their lit stoss
// sides and shadowed lee sides make parallel stripes, whose 2-D spectrum is concentrated in a
// few sharp peaks at ±k (k the ripple's wave vector, 1/λ along the crests' normal, projected
// on the chip's axes) and its harmonics. A target's highlight or shadow is a single blob whose
// spectrum is broad and smooth. So the ripples' share of the chip can be removed in the
// frequency domain, leaving the rest: the notch filter for periodic noise of image restoration
// (Gonzalez & Woods, "Digital Image Processing", 4th ed., 2018, Sec. 5.4, "periodic noise
// reduction using frequency domain filtering"), with the notches placed where the chip's own
// spectrum has isolated peaks.
//
// The method, on the chip's pixels (dB levels) less their mean:
//   1. the 2-D DFT X(ky, kx) (Eigen's FFT module, any size);
//   2. candidate peaks: bins that are a strict maximum of |X|² over their 3 x 3 neighbours, lie
//      outside the low frequencies ky² + kx² < min_radius_bins² (in bins of each axis)
//      (signed bin indices; there lie the chip's gross layout, the target's blob and its
//      shadow), and whose power is at least min_peak_ratio times the median power of their
//      ring (the bins whose frequency in cycles per pixel rounds to within one bin of theirs);
//   3. the strongest max_peaks candidates (each with its mirror -k, the same real stripes) are
//      notched: every bin of the (2 n + 1)² block around the peak (a ripple's period is not a
//      whole number of bins, so its power leaks to the neighbours) whose power is above the
//      ring median is scaled down to it, its phase kept;
//   4. the inverse DFT, real part, plus the mean.
// A chip with no isolated peak (a flat or cluttered seabed) comes back unchanged but for float
// rounding. Pure: the same chip and options give the same bytes.
#include "atr/chip.h"

namespace sonarloop::atr {

// The defaults were chosen on fig15's shadows (docs/sweep.md, "Sand ripples notched out"): a
// 5 x 5 notch removes a third more of the ripples' error than 3 x 3 (their period is not a
// whole number of bins, so their power leaks), wider ones no more; a 20 dB threshold passes no
// bin of speckle (an exponential bin power exceeds 100 times its median with probability
// 2^-100) and none of a sharp-edged shadow's sinc sidelobes, which reach 15-34 times their
// ring's median in tests/atr/chip_deripple_test.cpp; 10 dB notched those.
struct DerippleOptions {
  int max_peaks = 3;              // pairs (k, -k) notched at most: a fundamental, 2 harmonics
  double min_peak_ratio = 100.0;  // a peak's power over its ring's median power (20 dB)
  double min_radius_bins = 2.0;   // frequencies nearer 0 than this are never touched
  int notch_half_width_bins = 2;  // the notch: (2 n + 1)² bins around each peak
};

// What deripple_chip found: the notched peaks (signed bins, row then column frequency) and
// their power over their ring's median.
struct DerippleReport {
  struct Peak {
    int ky = 0, kx = 0;
    double ratio = 0.0;
  };
  std::vector<Peak> peaks;
};

// Throws std::invalid_argument naming the option out of range.
void validate_deripple(const DerippleOptions& o);

// The chip with its periodic texture notched out (above). Throws std::invalid_argument for an
// empty chip. `report`, when given, receives the notched peaks.
Chip deripple_chip(ChipView chip, const DerippleOptions& o = {}, DerippleReport* report = nullptr);

}  // namespace sonarloop::atr
