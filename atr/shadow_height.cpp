#include "atr/shadow_height.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace sonarloop::atr {
namespace {

bool positive_finite(double v) {
  return std::isfinite(v) && v > 0.0;
}

// The median of the chip's pixels (the seabed level of a chip mostly made of seabed).
float median_level(ChipView chip) {
  std::vector<float> v(chip.pixels.begin(), chip.pixels.end());
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

double shadow_height_m(double behind_m, double altitude_m, double ground_range_m) {
  // similar triangles: h / x = a / (G + x)
  return altitude_m * behind_m / (ground_range_m + behind_m);
}

double shadow_distance_m(double height_m, double altitude_m, double ground_range_m) {
  if (height_m >= altitude_m) return std::numeric_limits<double>::infinity();
  return height_m * ground_range_m / (altitude_m - height_m);
}

Chip shadow_height_chip(ChipView chip, const ShadowChipGeometry& g) {
  if (chip.width <= 0 || chip.height <= 0 ||
      chip.pixels.size() != static_cast<std::size_t>(chip.width) * chip.height) {
    throw std::invalid_argument("shadow_height_chip: empty chip or pixel count not width x height");
  }
  if (!positive_finite(g.altitude_m) || !positive_finite(g.ground_range_m) ||
      !positive_finite(g.range_start_m) || !positive_finite(g.bin_m)) {
    throw std::invalid_argument(
        "shadow_height_chip: altitude, ground range, range start and bin must be positive");
  }
  const int cols = chip.width;
  const float fill = median_level(chip);
  // the input column (fractional, pixel centres at integers) of each output column
  const int front =
      std::clamp(static_cast<int>(std::lround(kShadowHeightFront_m / g.bin_m)), 0, cols - 1);
  const int heights = cols - front;
  std::vector<double> source(static_cast<std::size_t>(cols));
  for (int j = 0; j < cols; ++j) {
    double x;  // ground distance behind the target's centre
    if (j < front) {
      x = -kShadowHeightFront_m + (j + 0.5) * g.bin_m;
    } else {
      const double h = (j - front + 0.5) * kShadowHeightMax_m / heights;
      x = shadow_distance_m(h, g.altitude_m, g.ground_range_m);
    }
    const double ground = g.ground_range_m + x;
    const double slant = std::hypot(g.altitude_m, ground);
    source[static_cast<std::size_t>(j)] =
        std::isfinite(slant) ? (slant - g.range_start_m) / g.bin_m - 0.5 : -1.0;
  }
  Chip out;
  out.width = cols;
  out.height = chip.height;
  out.pixels.resize(chip.pixels.size());
  for (int row = 0; row < chip.height; ++row) {
    const float* in = chip.pixels.data() + static_cast<std::size_t>(row) * cols;
    float* o = out.pixels.data() + static_cast<std::size_t>(row) * cols;
    for (int j = 0; j < cols; ++j) {
      const double c = source[static_cast<std::size_t>(j)];
      if (!(c >= 0.0) || c > cols - 1) {
        o[j] = fill;  // beyond the input chip: the seabed level
      } else if (cols == 1) {
        o[j] = in[0];
      } else {
        const int k = std::min(static_cast<int>(c), cols - 2);
        const double t = c - k;
        o[j] = static_cast<float>(in[k] + t * (in[k + 1] - in[k]));
      }
    }
  }
  return out;
}

}  // namespace sonarloop::atr
