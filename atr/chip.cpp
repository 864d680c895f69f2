#include "atr/chip.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sonarloop::atr {

const char* chip_status_name(ChipStatus s) {
  switch (s) {
    case ChipStatus::kOk:
      return "ok";
    case ChipStatus::kEmpty:
      return "empty";
    case ChipStatus::kWrongSize:
      return "wrong_size";
    case ChipStatus::kNotFinite:
      return "not_finite";
    case ChipStatus::kConstant:
      return "constant";
  }
  return "unknown";
}

std::string ChipCheck::reason() const {
  char buf[256];
  switch (status) {
    case ChipStatus::kOk:
      return "ok";
    case ChipStatus::kEmpty:
      std::snprintf(buf, sizeof buf, "empty chip (%d x %d pixels, %zu values)", width, height,
                    pixel_count);
      return buf;
    case ChipStatus::kWrongSize:
      if (pixel_count != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
        std::snprintf(buf, sizeof buf,
                      "malformed chip: %d x %d pixels declared but %zu values given", width, height,
                      pixel_count);
      } else {
        std::snprintf(buf, sizeof buf,
                      "wrong chip size: %d x %d pixels (width x height), the model expects %d x %d",
                      width, height, expected_width, expected_height);
      }
      return buf;
    case ChipStatus::kNotFinite:
      std::snprintf(buf, sizeof buf,
                    "non-finite pixel %g at row %d, column %d: chips must hold finite values",
                    static_cast<double>(value), row, col);
      return buf;
    case ChipStatus::kConstant:
      if (std_dev == 0.0) {
        std::snprintf(buf, sizeof buf,
                      "constant chip (all %d x %d pixels are %g, standard deviation 0): it cannot "
                      "be normalised by its standard deviation (eq. 9)",
                      width, height, static_cast<double>(value));
      } else {
        std::snprintf(buf, sizeof buf,
                      "nearly constant chip (%d x %d pixels around %g, standard deviation %g, "
                      "below %g of the pixel magnitude): it cannot be normalised (eq. 9)",
                      width, height, static_cast<double>(value), std_dev, kMinRelativeStdDev);
      }
      return buf;
  }
  return "unknown chip status";
}

ChipCheck check_chip_size(ChipView chip, int expected_width, int expected_height) {
  ChipCheck c;
  c.width = chip.width;
  c.height = chip.height;
  c.expected_width = expected_width;
  c.expected_height = expected_height;
  c.pixel_count = chip.pixels.size();
  if (chip.width <= 0 || chip.height <= 0 || chip.pixels.empty()) {
    c.status = ChipStatus::kEmpty;
  } else if (chip.pixels.size() !=
                 static_cast<std::size_t>(chip.width) * static_cast<std::size_t>(chip.height) ||
             (expected_width > 0 && expected_height > 0 &&
              (chip.width != expected_width || chip.height != expected_height))) {
    c.status = ChipStatus::kWrongSize;
  }
  return c;
}

ChipCheck normalise_chip(ChipView chip, std::span<float> out) {
  ChipCheck c = check_chip_size(chip);
  if (!c.ok()) return c;
  if (out.size() != chip.pixels.size()) {
    // a programming error of the caller, reported like a size mismatch
    c.status = ChipStatus::kWrongSize;
    c.expected_width = chip.width;
    c.expected_height = static_cast<int>(out.size() / static_cast<std::size_t>(chip.width));
    return c;
  }
  // finite check and mean, in double
  const std::size_t n = chip.pixels.size();
  double sum = 0.0;
  double max_abs = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const float v = chip.pixels[i];
    if (!std::isfinite(v)) {
      c.status = ChipStatus::kNotFinite;
      c.row = static_cast<int>(i / static_cast<std::size_t>(chip.width));
      c.col = static_cast<int>(i % static_cast<std::size_t>(chip.width));
      c.value = v;
      return c;
    }
    sum += v;
    max_abs = std::max(max_abs, std::abs(static_cast<double>(v)));
  }
  const double mean = sum / static_cast<double>(n);
  // population variance, two-pass (no cancellation)
  double ss = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = chip.pixels[i] - mean;
    ss += d * d;
  }
  const double sd = std::sqrt(ss / static_cast<double>(n));
  c.std_dev = sd;
  if (!(sd > kMinRelativeStdDev * max_abs) || sd == 0.0) {
    c.status = ChipStatus::kConstant;
    c.value = chip.pixels[0];
    return c;
  }
  const double inv = 1.0 / sd;
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = static_cast<float>((chip.pixels[i] - mean) * inv);
  }
  return c;
}

}  // namespace sonarloop::atr
