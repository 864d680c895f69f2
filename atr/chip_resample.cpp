#include "atr/chip_resample.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace sonarloop::atr {
namespace {

// One output pixel's input pixels and their weights (summing to 1).
struct Taps {
  int first = 0;               // first input pixel
  std::vector<double> weight;  // for input pixels first, first + 1, ...
};

// The area-average taps of each of `out` output pixels over `in` input pixels: output pixel j
// covers [j, j + 1) * in / out of the input, and each input pixel i weighs the length of
// [i, i + 1) inside it, divided by the covered length. Computed in units of 1 / out so that the
// bounds are integers (exact, whatever the ratio).
std::vector<Taps> area_taps(int in, int out) {
  std::vector<Taps> taps(static_cast<std::size_t>(out));
  const long long scale = out;  // one input pixel = `out` units, one output pixel = `in` units
  for (int j = 0; j < out; ++j) {
    const long long lo = static_cast<long long>(j) * in;  // in units
    const long long hi = lo + in;
    Taps& t = taps[static_cast<std::size_t>(j)];
    t.first = static_cast<int>(lo / scale);
    const int last = static_cast<int>((hi - 1) / scale);
    for (int i = t.first; i <= last; ++i) {
      const long long a = std::max(lo, i * scale);
      const long long b = std::min(hi, (i + 1) * scale);
      t.weight.push_back(static_cast<double>(b - a) / static_cast<double>(in));
    }
  }
  return taps;
}

}  // namespace

Chip resample_chip(ChipView chip, int width, int height) {
  if (width < 1 || height < 1) {
    throw std::invalid_argument("resample: target size " + std::to_string(width) + " x " +
                                std::to_string(height) + " is not positive");
  }
  const ChipCheck check = check_chip_size(chip);
  if (!check.ok()) throw std::invalid_argument("resample: " + check.reason());
  Chip out;
  out.width = width;
  out.height = height;
  if (chip.width == width && chip.height == height) {
    out.pixels.assign(chip.pixels.begin(), chip.pixels.end());
    return out;
  }
  // rows first: chip.height x width, in double
  const std::vector<Taps> cols = area_taps(chip.width, width);
  std::vector<double> rows(static_cast<std::size_t>(chip.height) * static_cast<std::size_t>(width));
  for (int r = 0; r < chip.height; ++r) {
    const float* src = chip.pixels.data() + static_cast<std::size_t>(r) * chip.width;
    for (int c = 0; c < width; ++c) {
      const Taps& t = cols[static_cast<std::size_t>(c)];
      double sum = 0.0;
      for (std::size_t k = 0; k < t.weight.size(); ++k)
        sum += t.weight[k] * src[static_cast<std::size_t>(t.first) + k];
      rows[static_cast<std::size_t>(r) * width + c] = sum;
    }
  }
  // then columns
  const std::vector<Taps> rws = area_taps(chip.height, height);
  out.pixels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (int r = 0; r < height; ++r) {
    const Taps& t = rws[static_cast<std::size_t>(r)];
    for (int c = 0; c < width; ++c) {
      double sum = 0.0;
      for (std::size_t k = 0; k < t.weight.size(); ++k)
        sum += t.weight[k] * rows[(static_cast<std::size_t>(t.first) + k) * width + c];
      out.pixels[static_cast<std::size_t>(r) * width + c] = static_cast<float>(sum);
    }
  }
  return out;
}

}  // namespace sonarloop::atr
