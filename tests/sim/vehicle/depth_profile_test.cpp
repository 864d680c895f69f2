#include "sim/vehicle/depth_profile.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

using namespace sonarloop::vehicle;

TEST_CASE("a constant profile", "[vehicle][depth]") {
  const DepthProfile p(12.5);
  CHECK(p.depth_at(-100.0) == 12.5);
  CHECK(p.depth_at(1e6) == 12.5);
  CHECK(p.slope_at(3.0) == 0.0);
}

TEST_CASE("smoothing keeps a linear profile and the rate bound", "[vehicle][depth]") {
  // a linear ramp is unchanged (away from the ends)
  std::vector<double> ramp;
  for (int k = 0; k <= 200; ++k)
    ramp.push_back(10.0 + 0.1 * k);  // slope 0.2 per m
  const DepthProfile linear(ramp, 0.5, 4.0);
  for (double s = 3.0; s <= 97.0; s += 0.37) {
    CHECK(linear.slope_at(s) == Approx(0.2).margin(1e-12));
    CHECK(linear.depth_at(s) == Approx(10.0 + 0.2 * s).epsilon(1e-13));
  }
  // beyond the knots: held at the end values
  CHECK(linear.depth_at(-10.0) == 10.0);
  CHECK(linear.depth_at(200.0) == Approx(30.0));
  CHECK(linear.slope_at(200.0) == 0.0);

  // a zig-zag at the maximum rate: the smoothed slope never exceeds it, is continuous, and the
  // profile stays within |Δslope|·W/8 of the knots' linear interpolant
  std::vector<double> zig;
  const double c = 0.125;  // per 0.5 m step: slope 0.25
  double z = 20.0;
  for (int k = 0; k <= 400; ++k) {
    zig.push_back(z);
    z += ((k / 20) % 2 == 0 ? c : -c);
  }
  const DepthProfile smooth(zig, 0.5, 5.0);
  double previous_slope = smooth.slope_at(0.0);
  for (double s = 0.0; s <= 200.0; s += 0.001) {
    const double slope = smooth.slope_at(s);
    CHECK(std::abs(slope) <= 0.25 + 1e-12);
    // curvature bound 2·0.25/5 per m
    CHECK(std::abs(slope - previous_slope) <= 2.0 * 0.25 / 5.0 * 0.001 + 1e-12);
    previous_slope = slope;
    const double x = s / 0.5;
    const auto k = std::min<std::size_t>(static_cast<std::size_t>(x), zig.size() - 2);
    const double knot_line = zig[k] + (x - static_cast<double>(k)) * (zig[k + 1] - zig[k]);
    CHECK(std::abs(smooth.depth_at(s) - knot_line) <= 0.5 * 5.0 / 8.0 + 1e-9);
  }
  // at the corners exactly that: deeper at the crest of the climb (s = 20 m, z = 20), shallower
  // at the bottom of the dive (s = 10 m, z = 22.5)
  CHECK(smooth.depth_at(20.0) == Approx(20.0 + 0.3125));
  CHECK(smooth.depth_at(10.0) == Approx(22.5 - 0.3125));
  // and a knot origin shifts it
  const DepthProfile shifted(zig, 0.5, 5.0, -7.0);
  CHECK(shifted.depth_at(13.0) == Approx(smooth.depth_at(20.0)));
  CHECK(shifted.slope_at(3.1) == Approx(smooth.slope_at(10.1)));
  // depth and its slope agree (numerical derivative)
  for (double s = 3.0; s < 197.0; s += 1.3) {
    const double h = 1e-4;
    CHECK((smooth.depth_at(s + h) - smooth.depth_at(s - h)) / (2 * h) ==
          Approx(smooth.slope_at(s)).margin(1e-5));  // (the slope has kinks: O(h) error)
  }
}

TEST_CASE("terrain following on a flat seabed is the commanded depth", "[vehicle][depth]") {
  const std::vector<double> seabed(100, 40.0);
  const auto z = terrain_following_depths(seabed, 0.5, 2.0, 10.0, 0.5, 50.0, 1.0);
  for (double v : z)
    CHECK(v == 30.0);
}

TEST_CASE("terrain following anticipates a step with its look-ahead", "[vehicle][depth]") {
  // seabed 40 m for 100 m, then a 10 m high wall (30 m) for 100 m, then 40 m again
  std::vector<double> seabed;
  for (int k = 0; k <= 600; ++k)
    seabed.push_back(k >= 200 && k < 400 ? 30.0 : 40.0);
  const double step = 0.5, speed = 2.0, rate = 0.5, altitude = 10.0;
  const double c = rate * step / speed;  // 0.125 m per step: 80 steps = 40 m to climb 10 m

  // look-ahead 60 m: climbing starts 80 steps before the wall; altitude never below 10 m
  const auto z = terrain_following_depths(seabed, step, speed, altitude, rate, 60.0, 1.0);
  CHECK(z[120] == 30.0);
  CHECK(z[121] == Approx(30.0 - c));
  CHECK(z[200] == Approx(20.0));
  for (std::size_t k = 0; k < z.size(); ++k) {
    CHECK(seabed[k] - z[k] >= altitude - 1e-9);
    if (k > 0) CHECK(std::abs(z[k] - z[k - 1]) <= c + 1e-12);
  }
  // after the wall it dives at the rate bound (no anticipation needed)
  CHECK(z[400] == Approx(20.0 + c));
  CHECK(z[478] == Approx(30.0 - c));
  CHECK(z[479] == Approx(30.0));

  // look-ahead too short (10 m < 40 m needed): it climbs late, altitude drops, rate still bounded
  const auto late = terrain_following_depths(seabed, step, speed, altitude, rate, 10.0, 1.0);
  double min_altitude = 1e300;
  for (std::size_t k = 0; k < late.size(); ++k) {
    min_altitude = std::min(min_altitude, seabed[k] - late[k]);
    if (k > 0) CHECK(std::abs(late[k] - late[k - 1]) <= c + 1e-12);
  }
  // it sees the wall 20 steps (10 m) ahead, so at the wall it has climbed 21·c of the 10 m
  CHECK(min_altitude == Approx(21 * c));  // 2.625 m

  // min_depth stops it below the surface
  const std::vector<double> shoal(50, 5.0);
  for (double v : terrain_following_depths(shoal, step, speed, altitude, rate, 60.0, 2.0)) {
    CHECK(v == 2.0);
  }
}
