// Chip checks and the eq. 9 normalisation: zero mean, unit standard deviation, gain and offset
// removed; degenerate chips rejected with a reason.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "atr/chip.h"

using namespace sonarloop::atr;

namespace {

Chip make_chip(int w, int h, float (*f)(int, int)) {
  Chip c;
  c.width = w;
  c.height = h;
  for (int r = 0; r < h; ++r) {
    for (int col = 0; col < w; ++col)
      c.pixels.push_back(f(r, col));
  }
  return c;
}

float ramp(int r, int c) {
  return static_cast<float>(3 * r + c * c);
}

}  // namespace

TEST_CASE("chip: normalisation gives zero mean and unit population standard deviation") {
  const Chip c = make_chip(5, 4, ramp);
  std::vector<float> out(c.pixels.size());
  const ChipCheck check = normalise_chip(c.view(), out);
  REQUIRE(check.ok());
  double sum = 0, ss = 0;
  for (float v : out)
    sum += v;
  for (float v : out)
    ss += static_cast<double>(v) * v;
  CHECK(sum / out.size() == Approx(0.0).margin(1e-6));
  CHECK(ss / out.size() == Approx(1.0).epsilon(1e-6));
  // by hand: the first pixel
  double mean = 0;
  for (float v : c.pixels)
    mean += v;
  mean /= c.pixels.size();
  double var = 0;
  for (float v : c.pixels)
    var += (v - mean) * (v - mean);
  const double sd = std::sqrt(var / c.pixels.size());
  CHECK(out[0] == Approx((c.pixels[0] - mean) / sd).epsilon(1e-6));
  CHECK(check.std_dev == Approx(sd));
}

TEST_CASE("chip: normalisation removes gain and offset") {
  const Chip c = make_chip(8, 8, ramp);
  Chip d = c;
  for (auto& v : d.pixels)
    v = 1000.0f + 0.25f * v;
  std::vector<float> a(c.pixels.size()), b(c.pixels.size());
  REQUIRE(normalise_chip(c.view(), a).ok());
  REQUIRE(normalise_chip(d.view(), b).ok());
  for (std::size_t i = 0; i < a.size(); ++i)
    CHECK(a[i] == Approx(b[i]).margin(1e-5));
}

TEST_CASE("chip: a constant chip is rejected, never turned into NaN") {
  Chip c = make_chip(6, 6, [](int, int) { return 17.0f; });
  std::vector<float> out(c.pixels.size(), -1.0f);
  const ChipCheck check = normalise_chip(c.view(), out);
  CHECK(check.status == ChipStatus::kConstant);
  CHECK(check.std_dev == 0.0);
  CHECK_THAT(check.reason(), Catch::Contains("constant chip") && Catch::Contains("17") &&
                                 Catch::Contains("standard deviation 0"));
  // all zeros too
  for (auto& v : c.pixels)
    v = 0.0f;
  CHECK(normalise_chip(c.view(), out).status == ChipStatus::kConstant);
  // a spread at float-rounding level of a large value counts as constant
  for (auto& v : c.pixels)
    v = 1.0e6f;
  c.pixels[3] = std::nextafter(1.0e6f, 2.0e6f);
  const ChipCheck nearly = normalise_chip(c.view(), out);
  CHECK(nearly.status == ChipStatus::kConstant);
  CHECK_THAT(nearly.reason(), Catch::Contains("nearly constant"));
  // but a real one-pixel difference is a valid chip
  c.pixels[3] = 1.0e6f + 100.0f;
  CHECK(normalise_chip(c.view(), out).ok());
}

TEST_CASE("chip: non-finite pixels are rejected with their position") {
  Chip c = make_chip(7, 3, ramp);
  std::vector<float> out(c.pixels.size());
  c.pixels[2 * 7 + 4] = std::numeric_limits<float>::quiet_NaN();
  ChipCheck check = normalise_chip(c.view(), out);
  CHECK(check.status == ChipStatus::kNotFinite);
  CHECK(check.row == 2);
  CHECK(check.col == 4);
  CHECK_THAT(check.reason(), Catch::Contains("row 2, column 4") && Catch::Contains("nan"));
  c.pixels[2 * 7 + 4] = 0.0f;
  c.pixels[0] = -std::numeric_limits<float>::infinity();
  check = normalise_chip(c.view(), out);
  CHECK(check.status == ChipStatus::kNotFinite);
  CHECK(check.row == 0);
  CHECK(check.col == 0);
}

TEST_CASE("chip: sizes are checked against the declaration and the model") {
  const Chip c = make_chip(8, 6, ramp);
  CHECK(check_chip_size(c.view()).ok());
  CHECK(check_chip_size(c.view(), 8, 6).ok());
  const ChipCheck wrong = check_chip_size(c.view(), 6, 8);
  CHECK(wrong.status == ChipStatus::kWrongSize);
  CHECK_THAT(wrong.reason(), Catch::Contains("8 x 6") && Catch::Contains("expects 6 x 8"));
  // declared size disagrees with the pixel count
  ChipView bad{8, 7, c.pixels};
  const ChipCheck malformed = check_chip_size(bad);
  CHECK(malformed.status == ChipStatus::kWrongSize);
  CHECK_THAT(malformed.reason(), Catch::Contains("56") || Catch::Contains("48 values"));
  CHECK(check_chip_size(ChipView{0, 0, {}}).status == ChipStatus::kEmpty);
  CHECK(check_chip_size(ChipView{-1, 4, c.pixels}).status == ChipStatus::kEmpty);
  std::vector<float> out(c.pixels.size());
  CHECK(normalise_chip(bad, out).status == ChipStatus::kWrongSize);
  CHECK(std::string(chip_status_name(ChipStatus::kConstant)) == "constant");
}
