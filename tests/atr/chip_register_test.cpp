// Registration of highlight chips: the centroid finds a bright blob wherever it is, the window
// cuts around any point, with the seabed level outside the chip.
#include "atr/chip_register.h"

#include <catch2/catch.hpp>
#include <stdexcept>

using namespace sonarloop::atr;

namespace {

// A 40 x 30 chip of seabed (level 100, with a small ramp so that no two pixels tie) and a
// bright 3 x 3 blob (level 200, brightest at its centre) centred at (row, col).
Chip blob_chip(int row, int col) {
  Chip c;
  c.width = 40;
  c.height = 30;
  c.pixels.resize(40 * 30);
  for (int r = 0; r < 30; ++r)
    for (int j = 0; j < 40; ++j)
      c.pixels[static_cast<std::size_t>(r) * 40 + j] = 100.0f + 0.001f * static_cast<float>(j);
  for (int dr = -1; dr <= 1; ++dr)
    for (int dc = -1; dc <= 1; ++dc)
      c.pixels[static_cast<std::size_t>(row + dr) * 40 + (col + dc)] =
          dr == 0 && dc == 0 ? 220.0f : 200.0f;
  return c;
}

}  // namespace

TEST_CASE("chip register: the highlight centroid is the bright blob's centre, wherever it is") {
  for (const auto& [row, col] : {std::pair{15, 20}, std::pair{4, 6}, std::pair{25, 35}}) {
    INFO("blob at " << row << ", " << col);
    const Chip c = blob_chip(row, col);
    const ChipPoint p = highlight_centroid(c.view());  // the brightest 1 %: 12 pixels
    CHECK(p.row == Approx(row).margin(0.05));
    CHECK(p.col == Approx(col).margin(0.05));
  }
  const Chip c = blob_chip(15, 20);
  CHECK_THROWS_AS(highlight_centroid(c.view(), 1.0), std::invalid_argument);
  CHECK_THROWS_AS(highlight_centroid(ChipView{}), std::invalid_argument);
}

TEST_CASE("chip register: a window cut around a point, the seabed level outside the chip") {
  const Chip c = blob_chip(15, 20);
  // a 5 x 5 window around the blob holds it at its centre
  const Chip w = chip_window(c.view(), 5, 5, {15.0, 20.0});
  REQUIRE(w.width == 5);
  REQUIRE(w.height == 5);
  CHECK(w.pixels[2 * 5 + 2] == 220.0f);
  CHECK(w.pixels[1 * 5 + 1] == 200.0f);
  CHECK(w.pixels[0] < 101.0f);
  // shifted by (2, -3) pixels: the blob moves the other way in the window
  const Chip s = chip_window(c.view(), 9, 9, {17.0, 17.0});
  CHECK(s.pixels[(4 - 2) * 9 + (4 + 3)] == 220.0f);
  // a window hanging over the chip's corner: outside pixels are the chip's median (seabed)
  const Chip corner = chip_window(c.view(), 6, 6, {0.0, 0.0});
  const float outside = corner.pixels[0];
  CHECK(outside >= 100.0f);
  CHECK(outside < 100.05f);
  // an even window puts its centre between pixels: its last pixel is (2.5, 2.5), rounded away
  CHECK(corner.pixels[5 * 6 + 5] == c.pixels[static_cast<std::size_t>(3) * 40 + 3]);
  CHECK_THROWS_AS(chip_window(c.view(), 0, 5, {0.0, 0.0}), std::invalid_argument);
}

TEST_CASE("chip register: re-centring on the centroid undoes a misplaced window") {
  const Chip c = blob_chip(15, 20);
  const Chip centred = chip_window(c.view(), 11, 11, {15.0, 20.0});
  // a detector's window 4 pixels off; registration finds the blob inside it and re-cuts
  const ChipPoint off{19.0, 17.0};
  const Chip cue = chip_window(c.view(), 21, 21, off);
  const ChipPoint p = highlight_centroid(cue.view());
  const ChipPoint in_chip{off.row - 10.0 + p.row, off.col - 10.0 + p.col};
  const Chip registered = chip_window(c.view(), 11, 11, in_chip);
  CHECK(registered.pixels == centred.pixels);
  CHECK(chip_window(c.view(), 11, 11, off).pixels != centred.pixels);
}
