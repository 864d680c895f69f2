// Area-average resampling (atr/chip_resample.h): exact on block images, keeps the mean, copies a
// chip of the same size, and rejects bad sizes.
#include "atr/chip_resample.h"

#include <catch2/catch.hpp>
#include <numeric>

using namespace sonarloop::atr;

namespace {

Chip scrambled_chip(int w, int h) {
  Chip c;
  c.width = w;
  c.height = h;
  c.pixels.resize(static_cast<std::size_t>(w * h));
  for (std::size_t i = 0; i < c.pixels.size(); ++i)
    c.pixels[i] = static_cast<float>((i * 37) % 101);
  return c;
}

double mean(const Chip& c) {
  return std::accumulate(c.pixels.begin(), c.pixels.end(), 0.0) /
         static_cast<double>(c.pixels.size());
}

}  // namespace

TEST_CASE("chip resample: halving averages 2 x 2 blocks, doubling repeats pixels") {
  Chip c;
  c.width = 4;
  c.height = 2;
  c.pixels = {0, 2, 10, 20, 4, 6, 30, 40};
  const Chip half = resample_chip(c.view(), 2, 1);
  REQUIRE(half.pixels.size() == 2);
  CHECK(half.pixels[0] == Approx(3.0));   // (0 + 2 + 4 + 6) / 4
  CHECK(half.pixels[1] == Approx(25.0));  // (10 + 20 + 30 + 40) / 4
  const Chip twice = resample_chip(half.view(), 4, 2);
  CHECK(twice.pixels == std::vector<float>{3, 3, 25, 25, 3, 3, 25, 25});
}

TEST_CASE("chip resample: fractional ratios weigh pixels by the area covered") {
  // 3 pixels to 2: output 0 covers input [0, 1.5): (a + 0.5 b) / 1.5
  Chip c;
  c.width = 3;
  c.height = 1;
  c.pixels = {3, 6, 9};
  const Chip r = resample_chip(c.view(), 2, 1);
  CHECK(r.pixels[0] == Approx((3.0 + 0.5 * 6.0) / 1.5));
  CHECK(r.pixels[1] == Approx((0.5 * 6.0 + 9.0) / 1.5));
  // 2 pixels to 3: output 1 straddles the boundary, half of each
  Chip d;
  d.width = 2;
  d.height = 1;
  d.pixels = {10, 40};
  CHECK(resample_chip(d.view(), 3, 1).pixels == std::vector<float>{10, 25, 40});
}

TEST_CASE("chip resample: the mean is kept at any ratio, same size is a copy") {
  const Chip c = scrambled_chip(37, 23);
  for (const auto& [w, h] : {std::pair{64, 64}, std::pair{16, 9}, std::pair{37, 5}}) {
    const Chip r = resample_chip(c.view(), w, h);
    CHECK(r.width == w);
    CHECK(r.height == h);
    CHECK(mean(r) == Approx(mean(c)).epsilon(1e-5));
  }
  CHECK(resample_chip(c.view(), 37, 23).pixels == c.pixels);
}

TEST_CASE("chip resample: bad sizes are errors") {
  const Chip c = scrambled_chip(4, 4);
  CHECK_THROWS_AS(resample_chip(c.view(), 0, 4), std::invalid_argument);
  CHECK_THROWS_AS(resample_chip(Chip{}.view(), 4, 4), std::invalid_argument);
}
