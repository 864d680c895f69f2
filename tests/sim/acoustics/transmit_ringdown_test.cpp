#include "sim/acoustics/transmit_ringdown.h"

#include <catch2/catch.hpp>

using namespace sonarloop::acoustics;

TEST_CASE("ringdown: the real Iver2 file's 8 saturated samples") {
  // 2.9280763 cm bins at 1460 m/s: bin 7's centre is at 300.8 µs, bin 8's at 340.9 µs
  CHECK(ringdown_bins(320e-6, 1460.0, 0.029280763) == 8);
  CHECK(ringdown_bins(300e-6, 1460.0, 0.029280763) == 7);
  CHECK(ringdown_bins(341e-6, 1460.0, 0.029280763) == 9);
}

TEST_CASE("ringdown: a bin counts when its centre's two-way time is before the end") {
  // 10 cm bins at 1500 m/s: centre k at (k + 0.5) · 133.33 µs
  const double bin_time = 2.0 * 0.1 / 1500.0;
  for (int k = 0; k < 20; ++k) {
    INFO("bin " << k);
    CHECK(ringdown_bins((k + 0.5) * bin_time * (1.0 + 1e-9), 1500.0, 0.1) == k + 1);
    CHECK(ringdown_bins((k + 0.5) * bin_time * (1.0 - 1e-9), 1500.0, 0.1) == k);
  }
}

TEST_CASE("ringdown: none without a ring-down") {
  CHECK(ringdown_bins(0.0, 1500.0, 0.05) == 0);
  CHECK(ringdown_bins(-1e-3, 1500.0, 0.05) == 0);
  CHECK(ringdown_bins(1e-6, 1500.0, 0.05) == 0);  // 0.75 mm: before the first bin's centre
}
