// Chip pre-processing (atr/chip_preprocess.h): crop, multilook against the N-look speckle law,
// levels against the chip's median.
#include "atr/chip_preprocess.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <stdexcept>

namespace sonarloop::atr {
namespace {

Chip ramp(int w, int h) {
  Chip c{w, h, std::vector<float>(static_cast<std::size_t>(w) * h)};
  for (int i = 0; i < w * h; ++i)
    c.pixels[static_cast<std::size_t>(i)] = static_cast<float>(i);
  return c;
}

double level_of_intensity(double i) {
  return 10.0 * std::log10(i) / kChipDbPerLevel;
}

TEST_CASE("crop keeps the central fraction of rows and columns", "[preprocess]") {
  const Chip c = ramp(6, 4);
  ChipPreprocess p;
  p.crop_fraction = 0.5;
  const Chip out = preprocess_chip(c.view(), p);
  REQUIRE(out.width == 3);
  REQUIRE(out.height == 2);
  // rows 1..2, columns 1..3 of the 6-wide ramp
  CHECK(out.pixels == std::vector<float>{7, 8, 9, 13, 14, 15});
  CHECK(cropped_size(60, 2.0 / 3.0) == 40);
  CHECK(cropped_size(1, 0.1) == 1);
}

TEST_CASE("multilook averages the intensity, not the dB level", "[preprocess]") {
  // 3 x 3 chip: 0 dB everywhere but +20 dB (100 x the intensity) in the centre
  const float base = 100.0f;
  const float bright = static_cast<float>(base + 20.0 / kChipDbPerLevel);
  Chip c{3, 3, std::vector<float>(9, base)};
  c.pixels[4] = bright;
  ChipPreprocess p;
  p.multilook_px = 3;
  const Chip out = preprocess_chip(c.view(), p);
  const double i0 = std::pow(10.0, base * kChipDbPerLevel / 10.0);
  // the centre's window is the whole chip: (8 + 100) / 9 of the base intensity
  CHECK(out.pixels[4] == Approx(level_of_intensity(i0 * 108.0 / 9.0)).epsilon(1e-6));
  // a corner's window holds the 2 x 2 pixels inside the chip: (3 + 100) / 4
  CHECK(out.pixels[0] == Approx(level_of_intensity(i0 * 103.0 / 4.0)).epsilon(1e-6));
  // an edge centre's window holds 2 x 3 pixels: (5 + 100) / 6
  CHECK(out.pixels[1] == Approx(level_of_intensity(i0 * 105.0 / 6.0)).epsilon(1e-6));
}

TEST_CASE("multilook k x k: the speckle's intensity CV falls to 1/k", "[preprocess]") {
  // single-look fully developed speckle: exponential intensity, CV 1 (Goodman 2007)
  const int n = 200;
  Chip c{n, n, std::vector<float>(static_cast<std::size_t>(n) * n)};
  std::mt19937_64 rng(7);
  std::exponential_distribution<double> expo(1.0);
  for (float& v : c.pixels)
    v = static_cast<float>(level_of_intensity(expo(rng)));
  for (int k : {1, 3, 5}) {
    ChipPreprocess p;
    p.multilook_px = k;
    const Chip out = preprocess_chip(c.view(), p);
    double s = 0.0, s2 = 0.0, m = 0.0;
    for (int r = k; r < n - k; ++r) {
      for (int col = k; col < n - k; ++col) {
        const double i = std::pow(10.0, out.at(r, col) * kChipDbPerLevel / 10.0);
        s += i;
        s2 += i * i;
        m += 1.0;
      }
    }
    const double mean = s / m;
    const double cv = std::sqrt(s2 / m - mean * mean) / mean;
    INFO("k = " << k);
    CHECK(cv == Approx(1.0 / k).epsilon(0.08));
  }
}

TEST_CASE("levels against the seabed (the chip's median)", "[preprocess]") {
  // median 10 (five of nine pixels); one highlight at 50, one shadow at 0
  Chip c{3, 3, {10, 10, 10, 10, 50, 10, 0, 12, 8}};
  ChipPreprocess p;
  p.levels = ChipLevels::kAboveSeabed;
  CHECK(preprocess_chip(c.view(), p).pixels == std::vector<float>{0, 0, 0, 0, 40, 0, 0, 2, 0});
  p.levels = ChipLevels::kBelowSeabed;
  CHECK(preprocess_chip(c.view(), p).pixels == std::vector<float>{0, 0, 0, 0, 0, 0, 10, 0, 2});
  p.levels = ChipLevels::kThreeLevel;
  p.threshold_db = 1.0;  // 4.25 levels
  CHECK(preprocess_chip(c.view(), p).pixels == std::vector<float>{0, 0, 0, 0, 1, 0, -1, 0, 0});
}

TEST_CASE("identity, labels and validation", "[preprocess]") {
  const Chip c = ramp(4, 4);
  CHECK(preprocess_chip(c.view(), ChipPreprocess{}).pixels == c.pixels);
  CHECK(preprocess_label(ChipPreprocess{}) == "eq. 9 only");
  CHECK(preprocess_label(ChipPreprocess{2.0 / 3.0, 3, ChipLevels::kAboveSeabed, 6.0}) ==
        "crop 0.67 + multilook 3 + above_seabed");
  CHECK(preprocess_label(ChipPreprocess{1.0, 3, ChipLevels::kThreeLevel, 6.0}) ==
        "multilook 3 + three_level 6 dB");
  CHECK_THROWS_AS(validate_preprocess(ChipPreprocess{0.0, 1, ChipLevels::kDb, 6.0}),
                  std::invalid_argument);
  CHECK_THROWS_AS(validate_preprocess(ChipPreprocess{1.0, 2, ChipLevels::kDb, 6.0}),
                  std::invalid_argument);
  CHECK_THROWS_AS(validate_preprocess(ChipPreprocess{1.0, 1, ChipLevels::kThreeLevel, 0.0}),
                  std::invalid_argument);
  CHECK_NOTHROW(validate_preprocess(ChipPreprocess{0.5, 5, ChipLevels::kThreeLevel, 3.0}));
}

TEST_CASE("adaptive crop: max(1.2 m, 10 pixels) a side, at most the whole chip", "[preprocess]") {
  CHECK(adaptive_crop_fraction(3.0, 0.05) == Approx(0.4));  // 1.2 m
  CHECK(adaptive_crop_fraction(3.0, 0.10) == Approx(0.4));  // 1.2 m = 12 pixels
  CHECK(adaptive_crop_fraction(3.0, 0.15) == Approx(0.5));  // 10 pixels = 1.5 m
  CHECK(adaptive_crop_fraction(3.0, 0.20) == Approx(2.0 / 3.0));
  CHECK(adaptive_crop_fraction(3.0, 0.30) == Approx(1.0));  // the whole chip
  CHECK(adaptive_crop_fraction(3.0, 0.50) == Approx(1.0));
}

}  // namespace
}  // namespace sonarloop::atr
