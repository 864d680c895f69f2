// Where the two sides of the chip convention (common/chip_convention.h) meet: a chip of
// `sonarloop dataset` (the simulator's ChipRenderer), streamed back ping by ping as a sonar would
// record it, is cut out of the waterfall by the onboard chip cutter (atr/) pixel for pixel, on
// either side; and its windows and shifted centres agree. (The cutter's own cases, on synthetic
// pings: tests/atr/chip_cutter_test.cpp.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "atr/chip_cutter.h"
#include "atr/waterfall.h"
#include "sim/render/chip_renderer.h"
#include "tests/atr/synthetic_pings.h"
#include "tests/sim/render/strip_sonar.h"

using namespace sonarloop;

namespace {

constexpr double kRes_m = 0.05;
constexpr float kOutsideDb = -40.0f;  // levels of the stream outside the chip's window

// Streams a dataset chip as the pings it was made of: ping k (in time order) at along-track
// position k R (heading north, no pitch), its line holding the chip's row for that ping at the
// chip's range bins. Returns where the target's centre lies in the stream.
atr::ChipCentre stream_chip(const render::ChipImage& chip, atr::Waterfall& w) {
  const xtf::XtfFileHeader h = testing::make_stream_header(4);  // float samples: exact levels
  const int k0 = static_cast<int>(std::lround(chip.range_start_m / kRes_m));
  const int bins = k0 + chip.cols + 20;
  const int side = chip.params.side;
  for (int k = 0; k < chip.rows; ++k) {
    std::vector<float> line(static_cast<std::size_t>(bins), kOutsideDb);
    const int row = side == 1 ? chip.rows - 1 - k : k;  // the dataset's convention
    for (int c = 0; c < chip.cols; ++c) {
      line[static_cast<std::size_t>(k0 + c)] =
          chip.level_db[static_cast<std::size_t>(row * chip.cols + c)];
    }
    const std::vector<float> other(static_cast<std::size_t>(bins), kOutsideDb);
    testing::PingPose pose;
    pose.number = static_cast<std::uint32_t>(k);
    pose.north_m = k * kRes_m;
    pose.speed_m_s = 2.0;
    pose.period_s = kRes_m / 2.0;
    pose.altitude_m = chip.params.altitude_m;
    REQUIRE(w.add(h, testing::make_ping(h, pose, side == 0 ? line : other, side == 1 ? line : other,
                                        kRes_m)) != atr::AddResult::kUnusable);
  }
  // ping k lies (k - centre_row + u) R from the closest approach: the centre is at
  // (centre_row - u) R, and at the slant range of the target's centre
  const double centre_row = 0.5 * (chip.rows - 1);
  return {side, (centre_row - chip.params.along_offset) * kRes_m, chip.slant_range_m};
}

// The first dataset chip index on `side`.
std::uint64_t index_on_side(const render::ChipDatasetSpec& spec, int side) {
  for (std::uint64_t i = 0;; ++i)
    if (render::chip_params(spec, i).side == side) return i;
}

render::ChipDatasetSpec small_spec() {
  render::ChipDatasetSpec spec;
  spec.classes = {targets::TargetType::kRockan, targets::TargetType::kCylinder};
  spec.seabeds = {render::builtin_dataset_seabed("flat")};
  spec.resolutions_m = {kRes_m};
  spec.sonar = sonarloop::testing::pailhas_strip_sonar();
  spec.seed = 3;
  return spec;
}

}  // namespace

TEST_CASE("chip cutter: a dataset chip streamed back is cut out pixel for pixel, both sides") {
  const render::ChipDatasetSpec spec = small_spec();
  const render::ChipRenderer renderer(spec);
  for (int side = 0; side < 2; ++side) {
    const render::ChipImage chip = renderer.render(index_on_side(spec, side), 0);
    INFO("side " << side << ", chip " << chip.params.index);
    REQUIRE(chip.params.side == side);
    atr::Waterfall w;
    const atr::ChipCentre centre = stream_chip(chip, w);
    atr::ChipCutter cutter(atr::highlight_chip_spec(chip.cols, chip.rows), 0, 0);
    REQUIRE(cutter.cut(w, centre) == atr::CutStatus::kOk);
    const atr::Chip& cut = cutter.context();
    REQUIRE(cut.width == chip.cols);
    REQUIRE(cut.height == chip.rows);
    int exact = 0, off_by_one = 0, worse = 0;
    for (std::size_t i = 0; i < chip.pixels.size(); ++i) {
      const float d = std::abs(cut.pixels[i] - static_cast<float>(chip.pixels[i]));
      exact += d == 0.0f;
      off_by_one += d == 1.0f;  // a level on a rounding boundary, after float samples
      worse += d > 1.0f;
    }
    INFO("pixels exact " << exact << ", off by one " << off_by_one << ", worse " << worse);
    CHECK(worse == 0);
    CHECK(exact >= static_cast<int>(0.995 * static_cast<double>(chip.pixels.size())));
    CHECK(cutter.gap_rows() == 0);
    // the chip shows something: its target
    CHECK(*std::max_element(cut.pixels.begin(), cut.pixels.end()) > 200.0f);
  }
}

TEST_CASE("chip cutter: windows and shifted centres agree") {
  const render::ChipDatasetSpec spec = small_spec();
  const render::ChipRenderer renderer(spec);
  for (int side = 0; side < 2; ++side) {
    const render::ChipImage chip = renderer.render(index_on_side(spec, side), 0);
    atr::Waterfall w;
    const atr::ChipCentre centre = stream_chip(chip, w);
    // 40 x 40 windows of 5 cm pixels: room to shift inside the streamed 3 m x 3 m
    atr::ChipCutter context(atr::ChipSpec{40, 40, kRes_m, kRes_m, {}}, 5, 7);
    REQUIRE(context.cut(w, centre) == atr::CutStatus::kOk);
    atr::ChipCutter plain(atr::ChipSpec{40, 40, kRes_m, kRes_m, {}}, 0, 0);
    atr::Chip a, b;
    for (const auto& [dr, dc] : {std::pair{0, 0}, {3, -5}, {-5, 7}, {2, 2}}) {
      INFO("side " << side << " shift " << dr << ", " << dc);
      context.window(dr, dc, a);
      REQUIRE(plain.cut(w, context.shifted(centre, dr, dc)) == atr::CutStatus::kOk);
      plain.window(0, 0, b);
      CHECK(a.pixels == b.pixels);
    }
    CHECK_THROWS_AS(context.window(6, 0, a), std::out_of_range);
  }
}
