// The onboard chip cutter (atr/chip_cutter.h) on synthetic pings: rows take the ping whose
// footprint is nearest at any ping spacing, a finer stream is averaged in power, and the cut's
// failure states. (A dataset chip streamed back and cut out pixel for pixel, which needs the
// simulator's chip renderer: tests/study/chip_cutter_dataset_test.cpp.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "atr/chip_cutter.h"
#include "atr/waterfall.h"
#include "common/chip_convention.h"
#include "tests/atr/synthetic_pings.h"

using namespace sonarloop;

namespace {
constexpr double kRes_m = 0.05;
}  // namespace

TEST_CASE("chip cutter: rows take the ping whose footprint is nearest, at any ping spacing") {
  // pings every 13.5 cm with pitch; each ping's line holds its own ping number
  const xtf::XtfFileHeader h = testing::make_stream_header();
  atr::Waterfall w;
  const double spacing = 0.135, altitude = 7.5;
  std::vector<double> footprint;
  for (int k = 0; k < 80; ++k) {
    testing::PingPose pose;
    pose.number = static_cast<std::uint32_t>(k);
    pose.north_m = k * spacing;
    pose.speed_m_s = 2.0;
    pose.period_s = spacing / 2.0;
    pose.altitude_m = altitude;
    pose.pitch_deg = 3.0 * std::sin(k * 0.4);
    footprint.push_back(pose.north_m +
                        altitude * std::tan(pose.pitch_deg * std::numbers::pi / 180.0));
    const std::vector<float> line(600, -1.0f * static_cast<float>(k % 50));
    w.add(h, testing::make_ping(h, pose, line, line, kRes_m));
  }
  atr::ChipCutter cutter(atr::highlight_chip_spec(60, 60), 0, 0);
  const atr::ChipCentre c{1, 5.0, 20.0};
  REQUIRE(cutter.cut(w, c) == atr::CutStatus::kOk);
  for (int row = 0; row < 60; ++row) {
    const double pos = c.along_m + ((59 - row) - 29.5) * kRes_m;  // starboard: last ping on top
    std::size_t best = 0;
    for (std::size_t k = 1; k < footprint.size(); ++k)
      if (std::abs(footprint[k] - pos) < std::abs(footprint[best] - pos)) best = k;
    CHECK(cutter.row_pings()[static_cast<std::size_t>(row)] == best);
  }
  // failures: not yet streamed, gone from the ring, outside the swath
  CHECK(cutter.cut(w, atr::ChipCentre{1, 10.5, 20.0}) == atr::CutStatus::kNotYet);
  CHECK(cutter.cut(w, atr::ChipCentre{1, 5.0, 29.5}) == atr::CutStatus::kOutside);
  atr::Waterfall small(20);
  for (int k = 0; k < 60; ++k) {
    testing::PingPose pose;
    pose.number = static_cast<std::uint32_t>(k);
    pose.north_m = k * spacing;
    const std::vector<float> line(600, -20.0f);
    small.add(h, testing::make_ping(h, pose, line, line, kRes_m));
  }
  CHECK(cutter.cut(small, atr::ChipCentre{1, 2.0, 20.0}) == atr::CutStatus::kGone);
}

TEST_CASE("chip cutter: a finer stream is averaged in power into the chip's pixels") {
  // stream bins of 2.5 cm, chip pixels of 5 cm: each pixel is the mean power of two bins
  const xtf::XtfFileHeader h = testing::make_stream_header(4);
  atr::Waterfall w;
  std::vector<float> line(1200);
  for (std::size_t k = 0; k < line.size(); ++k)
    line[k] = k % 2 ? -10.0f : -40.0f;
  for (int k = 0; k < 100; ++k) {
    testing::PingPose pose;
    pose.number = static_cast<std::uint32_t>(k);
    pose.north_m = k * 0.05;
    pose.speed_m_s = 2.0;
    pose.period_s = 0.025;
    w.add(h, testing::make_ping(h, pose, line, line, 0.025));
  }
  atr::ChipCutter cutter(atr::highlight_chip_spec(60, 60), 0, 0);
  REQUIRE(cutter.cut(w, atr::ChipCentre{0, 2.5, 15.0}) == atr::CutStatus::kOk);
  const double mean_db = 10.0 * std::log10(0.5 * (std::pow(10.0, -1.0) + std::pow(10.0, -4.0)));
  const float expected = chips::chip_pixel(mean_db, chips::ChipLevels{});
  for (float p : cutter.context().pixels)
    CHECK(p == expected);
}
