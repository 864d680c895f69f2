#pragma once
// Chips: small greyscale images of one contact (a target and its shadow), the classifier's input.
//
// Normalisation (Pailhas, Petillot & Capus 2010, Section 3.2, eq. 9 as we read it): each chip,
// taken as a vector of its n = width * height pixels, is centred on its own mean and divided by
// its own standard deviation, both taken over the chip's pixels:
//     x~_i = (x_i - mean(x)) / std(x),   std(x) = sqrt( (1/n) * sum_i (x_i - mean(x))^2 )
// (population standard deviation, so that |x~|^2 = n for every chip). This removes the sonar's
// gain and offset: a chip and a * chip + b (a > 0) normalise to the same vector.
//
// Degenerate chips are rejected with a reason instead of being turned into NaN: an empty chip, a
// chip of the wrong size, a non-finite pixel (NaN or infinity), and a constant chip (standard
// deviation 0, or so small against the pixel values that only float rounding would remain after
// division; see kMinRelativeStdDev).
//
// The checks and the normalisation are allocation-free (they run onboard, once per chip); only
// ChipCheck::reason() builds a string, for the error path.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sonarloop::atr {

// A non-owning view of a chip: row-major pixels, row 0 at the top.
struct ChipView {
  int width = 0;
  int height = 0;
  std::span<const float> pixels;  // (height x width)
};

// An owned chip.
struct Chip {
  int width = 0;
  int height = 0;
  std::vector<float> pixels;  // (height x width), row-major

  ChipView view() const { return {width, height, pixels}; }
  float at(int row, int col) const { return pixels[static_cast<std::size_t>(row) * width + col]; }
};

// A chip with its class label and, when known, the target's aspect angle, for training and for
// scoring against the truth.
struct LabelledChip {
  Chip chip;
  std::string label;                 // class name ("manta", ...); empty when unknown
  std::optional<double> aspect_deg;  // target aspect angle (deg), when known
  std::string source;                // where it came from (file path), for messages
};

// A chip left out of training or scoring, and why (a sentence a user can act on).
struct SkippedChip {
  std::string source;
  std::string reason;
};

// The standard deviation below which a chip counts as constant, relative to its largest absolute
// pixel value. Float pixels carry a relative rounding error of 2^-24 ~ 6e-8; a spread below
// 1e-6 of the pixel magnitude is indistinguishable from rounding, and dividing by it would only
// amplify rounding noise into a meaningless unit-variance chip.
inline constexpr double kMinRelativeStdDev = 1e-6;

enum class ChipStatus : int {
  kOk = 0,
  kEmpty = 1,      // no pixels (width or height <= 0)
  kWrongSize = 2,  // width x height differs from the model's chip size, or pixels.size() differs
  kNotFinite = 3,  // a pixel is NaN or infinite
  kConstant = 4,   // standard deviation 0 (or below kMinRelativeStdDev of the pixel magnitude)
};

// Short name of a status ("ok", "empty", "wrong_size", "not_finite", "constant").
const char* chip_status_name(ChipStatus s);

// The outcome of checking a chip, with the details needed to explain a rejection.
struct ChipCheck {
  ChipStatus status = ChipStatus::kOk;
  int width = 0, height = 0;                    // the chip's size
  int expected_width = 0, expected_height = 0;  // the size required (kWrongSize)
  std::size_t pixel_count = 0;                  // pixels.size() (kWrongSize, kEmpty)
  int row = -1, col = -1;                       // first non-finite pixel (kNotFinite)
  float value = 0.0f;                           // that pixel's value, or the constant value
  double std_dev = 0.0;                         // the chip's standard deviation (kConstant)

  bool ok() const { return status == ChipStatus::kOk; }
  // A sentence a user can act on, e.g. "constant chip (all 64 x 64 pixels are 17): standard
  // deviation 0, it cannot be normalised (eq. 9)". Allocates: call on the error path only.
  std::string reason() const;
};

// Checks the chip's shape: not empty, pixels.size() == width * height, and, when expected_width
// and expected_height are > 0, exactly that size. Allocation-free.
ChipCheck check_chip_size(ChipView chip, int expected_width = 0, int expected_height = 0);

// Eq. 9: checks that every pixel is finite and the chip is not constant, then writes the
// normalised chip (zero mean, unit population standard deviation) to `out`, which must hold
// chip.pixels.size() values. Sums are taken in double. On failure `out` is left unspecified.
// Allocation-free. Does not check the size against a model: call check_chip_size first.
ChipCheck normalise_chip(ChipView chip, std::span<float> out);

}  // namespace sonarloop::atr
