// The onboard detector on a synthetic waterfall with known objects and known distractors: each
// object is reported once, near its true position (along-track positions corrected for pitch),
// and nothing else is.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "atr/detector.h"
#include "atr/waterfall.h"
#include "tests/atr/synthetic_pings.h"

using namespace sonarloop;

namespace {

constexpr double kPeriod_s = 0.0675;  // 13.5 cm between pings at 2 m/s
constexpr double kAltitude_m = 7.5;
constexpr double kDetectorBin_m = 0.05;
constexpr int kDetectorBins = 1000;

using Thing = testing::SeabedObject;

struct Run {
  std::vector<atr::Detection> detections;
  atr::DetectorStats stats;
};

template <class Pitch>
Run run_line(int pings, const std::vector<Thing>& things, Pitch pitch) {
  const xtf::XtfFileHeader h = testing::make_stream_header();
  atr::Waterfall w;
  atr::Detector det;
  Run run;
  testing::stream_line(pings, things, pitch, h, [&](const xtf::XtfPing& p) {
    REQUIRE(w.add(h, p) == atr::AddResult::kAdded);
    for (const atr::Detection& d : det.process(w))
      run.detections.push_back(d);
  });
  for (const atr::Detection& d : det.finish(w))
    run.detections.push_back(d);
  run.stats = det.stats();
  return run;
}

// The detection of `t`, if one lies within 0.4 m along track and 0.5 m in ground range.
const atr::Detection* find(const Run& r, const Thing& t) {
  for (const auto& d : r.detections) {
    // the detector's centre is between the highlight and the shadow's start
    if (d.side == t.side && std::abs(d.along_m - t.along_m) < 0.4 &&
        std::abs(d.ground_m - t.ground_m) < 0.5)
      return &d;
  }
  return nullptr;
}

}  // namespace

TEST_CASE("detector: the known objects once each, none of the distractors") {
  const std::vector<Thing> objects = {
      {1, 10.0, 12.0, 0.8, 0.40},  // starboard, near
      {0, 20.0, 18.0, 1.0, 0.35},  // port
      {1, 34.0, 25.0, 0.6, 0.50},  // starboard, far
      {1, 45.0, 15.0, 1.0, 0.45},  // one object whose shadow breaks in two (below)
  };
  std::vector<Thing> things = objects;
  things.push_back({1, 45.5, 15.3, 0.5, 0.20, false, true});  // the second piece of that shadow
  things.push_back({1, 27.0, 15.0, 1.0, 0.50, false, true});  // a shadow without an echo
  things.push_back({0, 33.0, 20.0, 6.0, 0.40});               // a ripple-like line, 6 m long
  things.push_back({0, 40.0, 14.0, 0.3, 0.12});               // a small rock: a short shadow
  things.push_back({1, 40.0, 20.0, 1.0, 0.40, true, false});  // a bright patch, no shadow
  const Run r = run_line(420, things, [](int) { return 0.0; });
  for (const Thing& t : objects) {
    INFO("object at along " << t.along_m << " m, ground " << t.ground_m << " m");
    const atr::Detection* d = find(r, t);
    REQUIRE(d != nullptr);
    CHECK(d->height_m > 0.6 * t.height_m);
    CHECK(d->height_m < 1.3 * t.height_m);
    CHECK(d->pings >= 3);
  }
  CHECK(r.detections.size() == objects.size());
  CHECK(r.stats.reported == objects.size());
  CHECK(r.stats.rejected >= 1);         // the ripple line: too long
  CHECK(r.stats.below_threshold >= 1);  // the rock: under the height threshold
}

TEST_CASE("detector: along-track positions are footprint positions (pitch)") {
  // the vehicle pitches +-5 deg with a 3 s period: at 7.5 m altitude the footprint swings
  // +-0.66 m about the vehicle; objects are drawn where the footprints fall
  const std::vector<Thing> objects = {
      {1, 12.0, 12.0, 0.8, 0.4}, {0, 17.3, 14.0, 0.8, 0.4}, {1, 23.1, 16.0, 0.8, 0.4}};
  const auto pitch = [](int k) {
    return 5.0 * std::sin(2.0 * std::numbers::pi * k * kPeriod_s / 3.0);
  };
  const Run r = run_line(260, objects, pitch);
  REQUIRE(r.detections.size() == objects.size());
  for (const Thing& t : objects) {
    INFO("object at along " << t.along_m << " m");
    const atr::Detection* d = find(r, t);
    REQUIRE(d != nullptr);
    CHECK(std::abs(d->along_m - t.along_m) < 0.25);
  }
}

TEST_CASE("detector: background is the seabed's median level, robust to an object") {
  atr::Detector det;
  Rng rng(6, RngStream::kTraining, 91);
  std::vector<float> line =
      testing::seabed_line(rng, kDetectorBins, kDetectorBin_m, kAltitude_m, -25.0);
  testing::draw_object(line, kDetectorBin_m, kAltitude_m, Thing{1, 0.0, 15.0, 1.0, 0.5});
  std::vector<float> b(kDetectorBins);
  det.background(line, kDetectorBin_m, 200, b);
  // fully developed speckle: median of 10 log10(E) is 10 log10(ln 2) = -1.6 dB; a median of 7
  // medians of 20 speckled bins scatters by about half a dB
  const double expected = -25.0 + 10.0 * std::log10(std::log(2.0));
  double sum = 0.0;
  int n = 0;
  for (int k = 200; k < kDetectorBins; k += 25) {
    CHECK(std::abs(b[static_cast<std::size_t>(k)] - expected) < 1.5);
    sum += b[static_cast<std::size_t>(k)];
    ++n;
  }
  CHECK(std::abs(sum / n - expected) < 0.5);
  // at the object itself (highlight and 1.1 m of shadow), still the seabed
  CHECK(std::abs(
            b[static_cast<std::size_t>(testing::bin_of_ground(15.0, kAltitude_m, kDetectorBin_m))] -
            expected) < 1.5);
}

TEST_CASE("detector: options are checked") {
  atr::DetectorOptions o;
  o.background_blocks = 4;
  CHECK_THROWS_AS(atr::Detector(o), std::invalid_argument);
  o = {};
  o.settle_m = 0.1;
  CHECK_THROWS_AS(atr::Detector(o), std::invalid_argument);
}
