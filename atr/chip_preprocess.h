#pragma once
// Chip pre-processing before the eq. 9 normalisation: the factors of the chip pre-processing
// ablation (docs/sweep.md, `sweep --experiment ablation`). The paper (Pailhas, Petillot & Capus
// 2010, Sec. 3.2) feeds the chip itself to the eigen-subspace classifier; each step here is one
// standard sidescan ATR front-end operation that can be switched on alone, in this order:
//
//   crop       keep the central fraction f of the rows and of the columns: a smaller chip
//              holds less seabed texture around the same target (chip size factor).
//   multilook  k x k box average of the INTENSITY (pixels are dB, so averaged as 10^(L/10) and
//              taken back to dB): incoherent averaging of N = k² speckle cells, which lowers the
//              intensity's coefficient of variation from 1 (single-look, fully developed
//              speckle) to about 1/sqrt(N) at the cost of a k-pixel resolution (Goodman,
//              "Speckle Phenomena in Optics", 2007, Sec. 5.2 / the N-look gamma law). Edge
//              pixels average the part of the window inside the chip.
//   levels     relative to the chip's median level, the local seabed level (the target covers a
//              small part of a chip, so the median is the background reverberation):
//                above_seabed   max(L - L_med, 0): only what is brighter than the seabed, the
//                               highlight (ripple troughs and shadows become 0);
//                below_seabed   max(L_med - L, 0): only what is darker, the shadow;
//                three_level    +1 above L_med + T, -1 below L_med - T, 0 between: the
//                               highlight / shadow / background segmentation of classical
//                               sidescan ATR (e.g. Reed, Petillot & Bell, IEEE J. Ocean. Eng.
//                               28(1), 2003), with T = threshold_db.
//
// Pixels follow the chip convention of sim/render/chip_renderer.h: 0..255 over a fixed 60 dB
// span, so one level is kChipDbPerLevel dB (the offset is irrelevant to every step above).
// Pure functions: the same chip and options give the same bytes.
#include <cstdint>
#include <string>
#include <vector>

#include "atr/chip.h"

namespace sonarloop::atr {

// dB per pixel level: 60 dB over 255 levels (sim/render/chip_renderer.h, ChipLevels).
inline constexpr double kChipDbPerLevel = 60.0 / 255.0;

enum class ChipLevels : std::uint8_t {
  kDb = 0,
  kAboveSeabed = 1,
  kBelowSeabed = 2,
  kThreeLevel = 3
};

const char* chip_levels_name(ChipLevels l);  // "db", "above_seabed", "below_seabed", "three_level"

struct ChipPreprocess {
  double crop_fraction = 1.0;  // (0, 1]: central fraction of rows and columns kept
  int multilook_px = 1;        // odd k >= 1: k x k intensity average (1: off)
  ChipLevels levels = ChipLevels::kDb;
  double threshold_db = 6.0;  // T of three_level, > 0

  bool is_identity() const {
    return crop_fraction == 1.0 && multilook_px == 1 && levels == ChipLevels::kDb;
  }
  bool operator==(const ChipPreprocess&) const = default;
};

// Throws std::invalid_argument naming the field out of range.
void validate_preprocess(const ChipPreprocess& p);

// The crop that `sweep --crop auto` applies at pixel size R to a chip of side chip_side_m:
// keep a side of max(kMinCroppedSide_m, kMinCroppedPixels * R), at most the whole chip. The
// rule is read off the ablation (docs/sweep.md): on mixed seabeds the best highlight chip is
// 0.9-1.2 m at 5 cm (the largest target, 1 m, and its rim: less seabed texture to model),
// 1.5 m at 10-15 cm, 2 m at 20 cm and the whole 3 m from 25 cm, where a tighter chip keeps too
// few pixels (the target's outline spans only 4-5 of them) to carry the shape.
inline constexpr double kMinCroppedSide_m = 1.2;
inline constexpr double kMinCroppedPixels = 10.0;
double adaptive_crop_fraction(double chip_side_m, double pixel_m);

// A short label, e.g. "crop 0.67 + multilook 3 + three_level 6 dB"; "eq. 9 only" for identity.
std::string preprocess_label(const ChipPreprocess& p);

// The size of a chip of `width` x `height` after the crop: round(f * size), at least 1.
int cropped_size(int size, double crop_fraction);

// Work buffers of preprocess_into, sized once for a chip size so that the onboard classifier
// does not allocate per chip.
struct PreprocessScratch {
  std::vector<float> out;          // the result (cropped size)
  std::vector<double> level_work;  // intensities / counts, prefix sums, median copy
  void reserve(int width, int height);
};

// Applies the steps in order into scratch.out and returns a view of it (valid until the next
// call). The chip must be valid (check_chip_size); non-finite pixels pass through as they are
// (normalise_chip rejects them afterwards). Allocation-free once scratch.reserve() has been
// called for this chip size.
ChipView preprocess_into(ChipView chip, const ChipPreprocess& p, PreprocessScratch& scratch);

// The same, as an owned chip (allocates).
Chip preprocess_chip(ChipView chip, const ChipPreprocess& p);

}  // namespace sonarloop::atr
