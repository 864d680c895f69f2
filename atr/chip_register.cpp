#include "atr/chip_register.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace sonarloop::atr {
namespace {

void require_pixels(ChipView chip, const char* what) {
  if (chip.width <= 0 || chip.height <= 0 ||
      chip.pixels.size() != static_cast<std::size_t>(chip.width) * chip.height) {
    throw std::invalid_argument(std::string(what) +
                                ": empty chip or pixel count not width x height");
  }
}

// The value at quantile q of the chip's pixels (the k-th smallest, k = floor(q·(n − 1))).
float quantile_level(ChipView chip, double q) {
  std::vector<float> v(chip.pixels.begin(), chip.pixels.end());
  const auto k = static_cast<std::ptrdiff_t>(std::floor(q * static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[static_cast<std::size_t>(k)];
}

}  // namespace

ChipPoint highlight_centroid(ChipView chip, double quantile) {
  require_pixels(chip, "highlight_centroid");
  if (!(quantile >= 0.0 && quantile < 1.0)) {
    throw std::invalid_argument("highlight_centroid: quantile must be in [0, 1)");
  }
  const float level = quantile_level(chip, quantile);
  // weighted by the excess over the level (8-bit chips tie at the level by the hundred: those
  // weigh nothing); equal weights when nothing exceeds it
  double sw = 0.0, sr = 0.0, sc = 0.0, n = 0.0, nr = 0.0, nc = 0.0;
  for (int r = 0; r < chip.height; ++r) {
    for (int c = 0; c < chip.width; ++c) {
      const float v = chip.pixels[static_cast<std::size_t>(r) * chip.width + c];
      if (v < level) continue;
      const double w = static_cast<double>(v - level);
      sw += w;
      sr += w * r;
      sc += w * c;
      n += 1.0;
      nr += r;
      nc += c;
    }
  }
  if (sw > 0.0) return {sr / sw, sc / sw};
  return {nr / n, nc / n};  // n > 0: at least the quantile pixel itself
}

Chip chip_window(ChipView chip, int width, int height, ChipPoint centre) {
  require_pixels(chip, "chip_window");
  if (width < 1 || height < 1) throw std::invalid_argument("chip_window: empty window");
  const float fill = quantile_level(chip, 0.5);
  Chip out;
  out.width = width;
  out.height = height;
  out.pixels.resize(static_cast<std::size_t>(width) * height);
  const double r0 = centre.row - 0.5 * (height - 1);
  const double c0 = centre.col - 0.5 * (width - 1);
  for (int i = 0; i < height; ++i) {
    const long r = std::lround(r0 + i);
    for (int j = 0; j < width; ++j) {
      const long c = std::lround(c0 + j);
      const bool inside = r >= 0 && r < chip.height && c >= 0 && c < chip.width;
      out.pixels[static_cast<std::size_t>(i) * width + j] =
          inside ? chip.pixels[static_cast<std::size_t>(r) * chip.width + c] : fill;
    }
  }
  return out;
}

}  // namespace sonarloop::atr
