// Shadow chips in height coordinates: the geometry, and a synthetic shadow that must land on the
// same heights from any altitude.
#include "atr/shadow_height.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>

using namespace sonarloop::atr;

namespace {

constexpr float kSeabed = 100.0f;
constexpr float kShadow = 0.0f;

// A shadow chip of `cols` slant-range bins of bin_m (rows pings), column 0 starting 1 m of slant
// range before the target's centre, as the chip renderer cuts them: seabed everywhere but, in
// the middle third of the rows (a target is shorter than the chip along track), the shadow of a
// wall of height target_h standing at the target's centre (ground x from 0 to x(target_h)
// behind it), which is dark.
struct SyntheticShadow {
  Chip chip;
  ShadowChipGeometry geometry;
};

SyntheticShadow synthetic_shadow(double a, double g, double target_h, double bin_m, int cols,
                                 int rows) {
  SyntheticShadow s;
  s.geometry = {a, g, std::hypot(a, g) - 1.0, bin_m};
  s.chip.width = cols;
  s.chip.height = rows;
  s.chip.pixels.assign(static_cast<std::size_t>(cols) * rows, kSeabed);
  const double x_end = shadow_distance_m(target_h, a, g);
  for (int c = 0; c < cols; ++c) {
    const double slant = s.geometry.range_start_m + (c + 0.5) * bin_m;
    const double x = std::sqrt(slant * slant - a * a) - g;  // ground behind the centre
    if (x > 0.0 && x < x_end) {
      for (int r = rows / 3; r < rows - rows / 3; ++r)
        s.chip.pixels[static_cast<std::size_t>(r) * cols + c] = kShadow;
    }
  }
  return s;
}

// The height columns (after the front ones) darker than half way, in `row`.
int dark_height_columns(const Chip& c, double bin_m, int row) {
  const int front = static_cast<int>(std::lround(kShadowHeightFront_m / bin_m));
  int n = 0;
  for (int j = front; j < c.width; ++j)
    n += c.pixels[static_cast<std::size_t>(row) * c.width + j] < 0.5f * kSeabed ? 1 : 0;
  return n;
}

}  // namespace

TEST_CASE("shadow height: similar triangles, and x(h) inverts h(x)") {
  // the chip renderer's sizing example: 0.5 m tall, 25 m away, sonar 2 m up: 8.3 m of shadow
  CHECK(shadow_distance_m(0.5, 2.0, 25.0) == Approx(0.5 * 25.0 / 1.5));
  CHECK(shadow_height_m(0.5 * 25.0 / 1.5, 2.0, 25.0) == Approx(0.5));
  for (double a : {2.0, 5.0, 10.0}) {
    for (double x : {0.1, 1.0, 4.0, 9.0}) {
      INFO("a " << a << ", x " << x);
      CHECK(shadow_distance_m(shadow_height_m(x, a, 25.0), a, 25.0) == Approx(x).epsilon(1e-12));
    }
  }
  CHECK(std::isinf(shadow_distance_m(2.0, 2.0, 25.0)));
  CHECK(std::isinf(shadow_distance_m(3.0, 2.0, 25.0)));
  CHECK(shadow_height_m(0.0, 5.0, 25.0) == 0.0);
}

TEST_CASE("shadow height: one target's shadow covers the same heights from 2 m and from 10 m") {
  const double bin = 0.05;
  const int cols = 200, rows = 6;  // 10 m of slant range, as the chip convention's shadow chip
  const int mid = rows / 3;        // a row through the shadow (rows 2 and 3 are)
  const double h = 0.4;
  const auto low = synthetic_shadow(2.0, 25.0, h, bin, cols, rows);
  const auto high = synthetic_shadow(10.0, 25.0, h, bin, cols, rows);
  // in slant range the shadows differ by a factor of ~5 in length
  const auto dark_in = [&](const Chip& c) {
    int n = 0;
    for (int j = 0; j < cols; ++j)
      n += c.pixels[static_cast<std::size_t>(mid) * cols + j] == kShadow ? 1 : 0;
    return n;
  };
  CHECK(dark_in(low.chip) > 4 * dark_in(high.chip));

  const Chip pl = shadow_height_chip(low.chip.view(), low.geometry);
  const Chip ph = shadow_height_chip(high.chip.view(), high.geometry);
  REQUIRE(pl.width == cols);
  REQUIRE(pl.height == rows);
  const int front = static_cast<int>(std::lround(kShadowHeightFront_m / bin));
  const double expected = h / (kShadowHeightMax_m / (cols - front));  // columns below h
  // within one input pixel's height, bin·dh/dx = bin·a·G/(G + x)² <= bin·a/G, in output columns
  const double column_m = kShadowHeightMax_m / (cols - front);
  CHECK(std::abs(dark_height_columns(pl, bin, mid) - expected) <= 1 + bin * 2.0 / 25.0 / column_m);
  CHECK(std::abs(dark_height_columns(ph, bin, mid) - expected) <= 1 + bin * 10.0 / 25.0 / column_m);
  CHECK(dark_height_columns(pl, bin, 0) == 0);  // rows without a shadow stay seabed
  // the dark columns are the lowest heights, contiguous from the first height column
  const std::size_t m0 = static_cast<std::size_t>(mid) * cols;
  for (int j = front + 2; j < front + static_cast<int>(expected) - 2; ++j) {
    INFO("column " << j);
    CHECK(pl.pixels[m0 + j] < 0.5f * kSeabed);
    CHECK(ph.pixels[m0 + j] < 0.5f * kSeabed);
  }
  // rows with the same input are resampled alike
  for (int j = 0; j < cols; ++j) {
    CHECK(pl.pixels[m0 + cols + j] == pl.pixels[m0 + j]);
    CHECK(pl.pixels[cols + j] == pl.pixels[j]);
  }
}

TEST_CASE("shadow height: heights whose shadow ends beyond the chip read the seabed level") {
  // from 2 m, 0.6 m of height needs 10.7 m of ground behind the target; the chip holds ~9 m
  const auto s = synthetic_shadow(2.0, 25.0, 0.1, 0.05, 200, 3);
  const Chip p = shadow_height_chip(s.chip.view(), s.geometry);
  CHECK(p.pixels.back() == kSeabed);  // the median: most of the chip is seabed
  // a chip whose median is the shadow level fills with it instead
  Chip dark = s.chip;
  for (auto& v : dark.pixels)
    v = v == kSeabed ? 7.0f : v;
  CHECK(shadow_height_chip(dark.view(), s.geometry).pixels.back() == 7.0f);
}

TEST_CASE("shadow height: the same chip and geometry give the same pixels; bad input throws") {
  const auto s = synthetic_shadow(6.0, 25.0, 0.3, 0.1, 100, 3);
  CHECK(shadow_height_chip(s.chip.view(), s.geometry).pixels ==
        shadow_height_chip(s.chip.view(), s.geometry).pixels);
  ShadowChipGeometry bad = s.geometry;
  bad.altitude_m = 0.0;
  CHECK_THROWS_AS(shadow_height_chip(s.chip.view(), bad), std::invalid_argument);
  bad = s.geometry;
  bad.bin_m = std::nan("");
  CHECK_THROWS_AS(shadow_height_chip(s.chip.view(), bad), std::invalid_argument);
  CHECK_THROWS_AS(shadow_height_chip(ChipView{}, s.geometry), std::invalid_argument);
}
