#include "sim/vehicle/nav_sensor.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>
#include <thread>
#include <vector>

#include "common/rng.h"
#include "sim/vehicle/trajectory.h"
#include "tests/sim/vehicle/sample_moments.h"
#include "units/angles.h"

using namespace sonarloop;
using namespace sonarloop::vehicle;
using sonarloop::testing::sample_moments;
using sonarloop::testing::SampleMoments;

namespace {

// A trajectory with turns, sway, terrain following and roll: every field of the state moves.
Trajectory busy_trajectory() {
  TrajectoryDesc desc;
  desc.kind = TrajectoryKind::kLawnmower;
  desc.lawnmower.leg_length_m = 150.0;
  desc.lawnmower.line_spacing_m = 30.0;
  desc.lawnmower.legs = 3;
  desc.lawnmower.first_leg_heading = 2.5;  // crosses ±π
  desc.depth.mode = DepthMode::kAltitude;
  desc.sway = {0.5, 6.0, 0.0, 0.5};
  return Trajectory(desc,
                    [](double n, double e) { return 30.0 + 2.0 * std::sin(0.05 * n + 0.03 * e); });
}

NavNoiseDesc noisy() {
  NavNoiseDesc d;
  d.position_noise_sd_m = 0.8;
  d.position_drift_m_per_sqrt_s = 0.05;
  d.heading_bias = 0.01;
  d.heading_noise_sd = 0.004;
  d.heading_drift_rad_per_sqrt_s = 2e-4;
  d.attitude_noise_sd = 0.002;
  d.speed_noise_sd_m_s = 0.03;
  d.speed_scale_factor_error = 0.004;
  d.yaw_rate_noise_sd_rad_s = 0.001;
  d.depth_noise_sd_m = 0.05;
  d.altitude_noise_sd_m = 0.1;
  return d;
}

bool same(const NavSolution& a, const NavSolution& b) {
  // bitwise: NaN altitudes compare equal too
  const double x[] = {a.north_m,
                      a.east_m,
                      a.depth_m,
                      a.heading,
                      a.pitch,
                      a.roll,
                      a.speed_over_ground_m_s,
                      a.course_over_ground,
                      a.yaw_rate,
                      a.altitude_m};
  const double y[] = {b.north_m,
                      b.east_m,
                      b.depth_m,
                      b.heading,
                      b.pitch,
                      b.roll,
                      b.speed_over_ground_m_s,
                      b.course_over_ground,
                      b.yaw_rate,
                      b.altitude_m};
  return a.t == b.t && std::memcmp(x, y, sizeof x) == 0;
}

}  // namespace

TEST_CASE("zero noise publishes exactly the truth", "[vehicle][nav]") {
  const Trajectory tr = busy_trajectory();
  const NavSensorModel nav(NavNoiseDesc{}, 42);
  for (double t = 0.0; t < tr.duration_s(); t += 0.37) {
    const VehicleState s = tr.state_at(from_seconds(t));
    const NavSolution n = nav.measure(s);
    CHECK(n.t == s.t);
    CHECK(n.north_m == s.pose.position_W.x());
    CHECK(n.east_m == s.pose.position_W.y());
    CHECK(n.depth_m == s.pose.position_W.z());
    CHECK(n.heading == wrap_to_two_pi(s.pose.yaw));
    CHECK(n.pitch == s.pose.pitch);
    CHECK(n.roll == s.pose.roll);
    CHECK(n.yaw_rate == s.yaw_rate);
    CHECK(n.altitude_m == s.altitude_m);
    CHECK(n.speed_over_ground_m_s == s.speed_m_s);
    CHECK(n.course_over_ground == wrap_to_two_pi(std::atan2(s.velocity_W.y(), s.velocity_W.x())));
    CHECK(n.error.horizontal_m == 0.0);
    CHECK(std::abs(n.error.heading) < 1e-15);
  }
}

TEST_CASE("the nav model is deterministic and independent of call order and thread",
          "[vehicle][nav]") {
  const Trajectory tr = busy_trajectory();
  const NavSensorModel nav(noisy(), 1234);
  // 2000 times over the mission, some sharing a noise step
  Rng rng(99, RngStream::kNavNoise);
  std::vector<VehicleState> states;
  for (int i = 0; i < 2000; ++i) {
    states.push_back(tr.state_at(from_seconds(rng.uniform(0.0, tr.duration_s()))));
  }
  std::vector<NavSolution> forward;
  for (const auto& s : states)
    forward.push_back(nav.measure(s));

  // reverse order, and a fresh model with the same seed
  const NavSensorModel twin(noisy(), 1234);
  for (std::size_t i = states.size(); i-- > 0;) {
    CHECK(same(nav.measure(states[i]), forward[i]));
    CHECK(same(twin.measure(states[i]), forward[i]));
  }
  // four threads, interleaved
  std::vector<NavSolution> threaded(states.size());
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < 4; ++k) {
    threads.emplace_back([&, k] {
      for (std::size_t i = k; i < states.size(); i += 4)
        threaded[i] = nav.measure(states[i]);
    });
  }
  for (auto& t : threads)
    t.join();
  int mismatches = 0;
  for (std::size_t i = 0; i < states.size(); ++i)
    mismatches += same(threaded[i], forward[i]) ? 0 : 1;
  CHECK(mismatches == 0);

  // another seed gives other errors
  const NavSensorModel other(noisy(), 1235);
  CHECK(other.measure(states[0]).north_m != forward[0].north_m);
}

TEST_CASE("white noise has the configured standard deviation", "[vehicle][nav]") {
  NavNoiseDesc d;
  d.position_noise_sd_m = 0.8;
  d.heading_noise_sd = 0.004;
  d.attitude_noise_sd = 0.002;
  d.yaw_rate_noise_sd_rad_s = 0.001;
  d.depth_noise_sd_m = 0.05;
  d.altitude_noise_sd_m = 0.1;
  d.speed_noise_sd_m_s = 0.03;
  const NavSensorModel nav(d, 7);

  VehicleState truth;
  truth.pose.position_W = Vec3(10.0, 20.0, 30.0);
  truth.pose.yaw = 1.0;
  truth.velocity_W = Vec3(2.0 * std::cos(1.0), 2.0 * std::sin(1.0), 0.0);
  truth.speed_m_s = 2.0;
  truth.altitude_m = 12.0;

  std::vector<double> north, east, heading, pitch, roll, rate, depth, altitude, speed;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    truth.t = static_cast<SimTime>(i) * 10'000'000;  // one sample per 10 ms noise step
    const NavSolution s = nav.measure(truth);
    north.push_back(s.error.north_m);
    east.push_back(s.error.east_m);
    heading.push_back(s.error.heading);
    pitch.push_back(s.error.pitch);
    roll.push_back(s.error.roll);
    rate.push_back(s.error.yaw_rate);
    depth.push_back(s.error.depth_m);
    altitude.push_back(s.error.altitude_m);
    speed.push_back(s.error.speed_m_s);
  }
  struct Case {
    const char* name;
    const std::vector<double>* v;
    double sd;
  };
  for (const Case& c :
       {Case{"north", &north, 0.8}, Case{"east", &east, 0.8}, Case{"heading", &heading, 0.004},
        Case{"pitch", &pitch, 0.002}, Case{"roll", &roll, 0.002}, Case{"yaw rate", &rate, 0.001},
        Case{"depth", &depth, 0.05}, Case{"altitude", &altitude, 0.1},
        Case{"speed", &speed, 0.03}}) {
    const SampleMoments m = sample_moments(*c.v);
    std::printf("white %-8s sd %.6g (configured %.6g, ratio %.4f), mean %+.2g\n", c.name, m.sd,
                c.sd, m.sd / c.sd, m.mean);
    CHECK(m.sd / c.sd == Approx(1.0).epsilon(0.05));
    CHECK(std::abs(m.mean) < 4.0 * c.sd / std::sqrt(n));
  }
}

TEST_CASE("heading bias, random-walk drift and speed scale factor", "[vehicle][nav]") {
  SECTION("bias is the mean heading error; the course error follows it") {
    NavNoiseDesc d;
    d.heading_bias = 0.02;
    d.heading_noise_sd = 0.005;
    const NavSensorModel nav(d, 3);
    VehicleState truth;
    truth.pose.yaw = -std::numbers::pi + 0.01;  // the bias wraps the published heading past π
    truth.velocity_W = Vec3(-2.0, 0.0, 0.0);
    truth.speed_m_s = 2.0;
    std::vector<double> heading, course;
    for (int i = 0; i < 10000; ++i) {
      truth.t = static_cast<SimTime>(i) * 10'000'000;
      const NavSolution s = nav.measure(truth);
      heading.push_back(s.error.heading);
      course.push_back(s.error.course);
    }
    CHECK(sample_moments(heading).mean == Approx(0.02).margin(4 * 0.005 / 100.0));
    CHECK(sample_moments(course).mean == Approx(0.02).margin(4 * 0.005 / 100.0));
  }

  SECTION("drift variance grows linearly with time") {
    NavNoiseDesc d;
    d.position_drift_m_per_sqrt_s = 0.1;
    d.heading_drift_rad_per_sqrt_s = 1e-3;
    VehicleState truth;
    const int seeds = 3000;
    for (double t_s : {30.0, 300.0, 3000.0}) {
      truth.t = from_seconds(t_s);
      std::vector<double> north, east, heading;
      for (int seed = 0; seed < seeds; ++seed) {
        const NavSolution s = NavSensorModel(d, static_cast<std::uint64_t>(seed)).measure(truth);
        north.push_back(s.error.north_m);
        east.push_back(s.error.east_m);
        heading.push_back(s.error.heading);
      }
      const double expected_position = 0.1 * 0.1 * t_s;
      const double expected_heading = 1e-6 * t_s;
      const double vn = std::pow(sample_moments(north).sd, 2),
                   ve = std::pow(sample_moments(east).sd, 2);
      const double vh = std::pow(sample_moments(heading).sd, 2);
      std::printf("drift t = %5.0f s: var north/expected %.3f, east %.3f, heading %.3f\n", t_s,
                  vn / expected_position, ve / expected_position, vh / expected_heading);
      CHECK(vn / expected_position == Approx(1.0).epsilon(0.1));
      CHECK(ve / expected_position == Approx(1.0).epsilon(0.1));
      CHECK(vh / expected_heading == Approx(1.0).epsilon(0.1));
    }
    // a drift is slow: two solutions 10 ms apart differ by ~q·sqrt(10 ms)·(interpolated) only
    const NavSensorModel nav(d, 5);
    truth.t = from_seconds(1000.0);
    const double a = nav.measure(truth).error.north_m;
    truth.t += 10'000'000;
    const double b = nav.measure(truth).error.north_m;
    CHECK(std::abs(a - b) < 0.01);
  }

  SECTION("scale factor") {
    NavNoiseDesc d;
    d.speed_scale_factor_error = 0.004;
    const NavSensorModel nav(d, 3);
    VehicleState truth;
    truth.velocity_W = Vec3(1.2, -1.6, 0.3);
    truth.speed_m_s = 2.0;
    const NavSolution s = nav.measure(truth);
    CHECK(s.speed_over_ground_m_s == Approx(2.0 * 1.004));
    CHECK(s.error.speed_m_s == Approx(0.008));
    CHECK(s.course_over_ground == Approx(wrap_to_two_pi(std::atan2(-1.6, 1.2))));
  }
}

TEST_CASE("unknown altitude stays unknown; bad noise descriptions are refused", "[vehicle][nav]") {
  NavNoiseDesc d;
  d.altitude_noise_sd_m = 0.1;
  const NavSensorModel nav(d, 1);
  VehicleState truth;  // altitude NaN
  const NavSolution s = nav.measure(truth);
  CHECK(std::isnan(s.altitude_m));
  CHECK(s.error.altitude_m == 0.0);

  d.heading_noise_sd = -1.0;
  CHECK_THROWS_WITH(NavSensorModel(d, 1), Catch::Contains("nav.heading_noise_sd = -1"));
}
