// Sand-ripple texture suppression: stripes laid over a target's shadow are notched out and the
// shadow kept; speckle alone (no stripes) is left as it was; the options are checked.
#include "atr/chip_deripple.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>

using namespace sonarloop::atr;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A shadow chip's layout without ripples: seabed at 100 with speckle-like noise (exponential
// intensity in dB, as fully developed speckle: sd 5.6 dB, in levels of 60/255 dB), a dark
// rectangle of rows [h/3, 2h/3) and columns [w/4, w/2) (the target's shadow) at 20.
Chip shadow_layout(int w, int h, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::exponential_distribution<double> speckle(1.0);
  Chip c{w, h, std::vector<float>(static_cast<std::size_t>(w) * h)};
  for (int r = 0; r < h; ++r) {
    for (int col = 0; col < w; ++col) {
      const bool shadow = r >= h / 3 && r < 2 * h / 3 && col >= w / 4 && col < w / 2;
      const double db = 10.0 * std::log10(speckle(rng)) / (60.0 / 255.0);
      c.pixels[static_cast<std::size_t>(r) * w + col] =
          static_cast<float>((shadow ? 20.0 : 100.0) + db);
    }
  }
  return c;
}

// Ripple stripes of `amplitude` levels and wavelength `lambda_px` pixels, crests normal to the
// direction `angle` (radians from the columns' axis), added to the chip.
Chip with_ripples(Chip c, double lambda_px, double angle, double amplitude) {
  for (int r = 0; r < c.height; ++r) {
    for (int col = 0; col < c.width; ++col) {
      const double along = col * std::cos(angle) + r * std::sin(angle);
      c.pixels[static_cast<std::size_t>(r) * c.width + col] +=
          static_cast<float>(amplitude * std::sin(2.0 * kPi * along / lambda_px));
    }
  }
  return c;
}

double rms_difference(const Chip& a, const Chip& b) {
  REQUIRE(a.pixels.size() == b.pixels.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const double d = a.pixels[i] - b.pixels[i];
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(a.pixels.size()));
}

double mean(const Chip& c) {
  double s = 0.0;
  for (float p : c.pixels)
    s += p;
  return s / static_cast<double>(c.pixels.size());
}

}  // namespace

TEST_CASE("deripple: stripes over a shadow chip are notched out, the shadow kept",
          "[chip_deripple]") {
  // a 5 cm shadow chip of 3 m x 10 m: 60 pings of 200 bins; 0.8 m ripples = 16 pixels, at an
  // angle, so that their period is not a whole number of DFT bins on either axis
  const Chip clean = shadow_layout(200, 60, 7);
  const double angle = GENERATE(0.3, 1.1);
  const Chip rippled = with_ripples(clean, 16.0, angle, 25.0);
  DerippleReport report;
  const Chip out = deripple_chip(rippled.view(), {}, &report);
  REQUIRE(out.width == rippled.width);
  REQUIRE(out.height == rippled.height);

  const double before = rms_difference(rippled, clean);  // 25 / sqrt(2) = 17.7 levels
  const double after = rms_difference(out, clean);
  INFO("angle " << angle << ": rms difference from the clean chip " << before << " -> " << after);
  CHECK(before == Approx(25.0 / std::sqrt(2.0)).epsilon(0.05));
  CHECK(after < 0.5 * before);  // three quarters of the stripes' power gone
  CHECK(mean(out) == Approx(mean(rippled)).margin(1e-3));

  // the strongest notch is the stripes' own frequency (one of each mirror pair: ky >= 0)
  REQUIRE(!report.peaks.empty());
  const double ky = 60.0 * std::sin(angle) / 16.0, kx = 200.0 * std::cos(angle) / 16.0;
  CHECK(std::abs(report.peaks[0].ky - ky) <= 1.0);
  CHECK(std::abs(report.peaks[0].kx - kx) <= 1.0);
  CHECK(report.peaks[0].ratio >= DerippleOptions{}.min_peak_ratio);

  // the shadow's contrast survives: its mean level against the seabed's
  auto region_mean = [](const Chip& c, int r0, int r1, int c0, int c1) {
    double s = 0.0;
    for (int r = r0; r < r1; ++r)
      for (int col = c0; col < c1; ++col)
        s += c.at(r, col);
    return s / ((r1 - r0) * (c1 - c0));
  };
  const double contrast_clean =
      region_mean(clean, 0, 20, 100, 200) - region_mean(clean, 20, 40, 50, 100);
  const double contrast_out = region_mean(out, 0, 20, 100, 200) - region_mean(out, 20, 40, 50, 100);
  CHECK(contrast_out == Approx(contrast_clean).epsilon(0.1));
}

TEST_CASE("deripple: speckle and a shadow without stripes come back unchanged", "[chip_deripple]") {
  // the default threshold, 20 dB over the ring's median power: no speckle bin passes it (an
  // exponential bin power exceeds 100 times its median with probability 2^-100), nor the sinc
  // sidelobes of the shadow's sharp edges; at 10 dB those are notched
  int notched_default = 0, notched_10db = 0;
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    const Chip clean = shadow_layout(200, 60, seed);
    DerippleReport report;
    const Chip out = deripple_chip(clean.view(), {}, &report);
    notched_default += static_cast<int>(report.peaks.size());
    CHECK(rms_difference(out, clean) < 1e-3);
    DerippleOptions o;
    o.min_peak_ratio = 10.0;
    deripple_chip(clean.view(), o, &report);
    notched_10db += static_cast<int>(report.peaks.size());
    for (const auto& p : report.peaks) {
      INFO("a sidelobe of the shadow's edges at (" << p.ky << ", " << p.kx << "), " << p.ratio);
      // on an axis: the sidelobes of the shadow's along-track or across-track edges
      CHECK(std::min(std::abs(p.ky), std::abs(p.kx)) <= 1);
      CHECK(p.ratio < DerippleOptions{}.min_peak_ratio);
    }
  }
  CHECK(notched_default == 0);
  CHECK(notched_10db > 0);
}

TEST_CASE("deripple: the same chip gives the same bytes; small chips pass through",
          "[chip_deripple]") {
  const Chip rippled = with_ripples(shadow_layout(200, 60, 3), 16.0, 0.7, 20.0);
  const Chip a = deripple_chip(rippled.view());
  const Chip b = deripple_chip(rippled.view());
  CHECK(a.pixels == b.pixels);
  CHECK(a.pixels != rippled.pixels);

  const Chip tiny{3, 3, std::vector<float>(9, 5.0f)};
  CHECK(deripple_chip(tiny.view()).pixels == tiny.pixels);
}

TEST_CASE("deripple: options and chips out of range are refused", "[chip_deripple]") {
  const Chip c = shadow_layout(40, 40, 1);
  DerippleOptions o;
  o.max_peaks = 0;
  CHECK_THROWS_AS(deripple_chip(c.view(), o), std::invalid_argument);
  o = {};
  o.min_peak_ratio = 0.5;
  CHECK_THROWS_AS(deripple_chip(c.view(), o), std::invalid_argument);
  o = {};
  o.min_radius_bins = std::nan("");
  CHECK_THROWS_AS(deripple_chip(c.view(), o), std::invalid_argument);
  const std::vector<float> none;
  CHECK_THROWS_AS(deripple_chip(ChipView{0, 0, none}), std::invalid_argument);
  const std::vector<float> short_row(5, 1.0f);
  CHECK_THROWS_AS(deripple_chip(ChipView{3, 2, short_row}), std::invalid_argument);
}
