// The vehicle's attitude along its trajectory (sim/vehicle/trajectory.h): pitch with the climb,
// roll in a turn, waves rocking it (about its bank in a turn) and sway offsetting it sideways.
#include "sim/vehicle/trajectory.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "tests/sim/vehicle/trajectory_fixtures.h"
#include "units/angles.h"

using namespace sonarloop;
using namespace sonarloop::vehicle;
using sonarloop::kRadPerDeg;
using namespace sonarloop::vehicle::trajectory_test;

namespace {

// Every field of two states, exactly (a NaN altitude equals a NaN altitude).
void check_same_state(const VehicleState& a, const VehicleState& b) {
  CHECK(a.t == b.t);
  CHECK(a.pose.position_W == b.pose.position_W);
  CHECK(a.pose.yaw == b.pose.yaw);
  CHECK(a.pose.pitch == b.pose.pitch);
  CHECK(a.pose.roll == b.pose.roll);
  CHECK(a.velocity_W == b.velocity_W);
  CHECK(a.yaw_rate == b.yaw_rate);
  CHECK(a.speed_m_s == b.speed_m_s);
  CHECK((a.altitude_m == b.altitude_m || (std::isnan(a.altitude_m) && std::isnan(b.altitude_m))));
  CHECK(a.path_s_m == b.path_s_m);
  CHECK(a.leg == b.leg);
}

}  // namespace

TEST_CASE("pitch is nose up when climbing, nose down when diving", "[vehicle][trajectory]") {
  // seabed rising 0.1 m per m northwards for 300 m, then falling: climb then dive at 0.2 m/s
  TrajectoryDesc desc = altitude_line(10.0, 50.0);
  desc.straight_length_m = 600.0;
  const Trajectory tr(desc, [](double north, double) {
    return north < 300.0 ? 80.0 - 0.1 * north : 50.0 + 0.1 * (north - 300.0);
  });
  const VehicleState climbing = tr.state_at(at_s(75.0));  // 150 m north
  CHECK(climbing.velocity_W.z() == Approx(-0.2).epsilon(1e-9));
  CHECK(climbing.pose.pitch > 0.0);
  CHECK(climbing.pose.pitch == Approx(std::atan2(0.2, 2.0)).epsilon(1e-9));
  const VehicleState diving = tr.state_at(at_s(225.0));  // 450 m north
  CHECK(diving.velocity_W.z() == Approx(0.2).epsilon(1e-9));
  CHECK(diving.pose.pitch < 0.0);
  CHECK(diving.pose.pitch == Approx(-std::atan2(0.2, 2.0)).epsilon(1e-9));
  // R_WV of a nose-up pitch tips the body x axis up (negative z in NED)
  CHECK((climbing.pose.R_WV() * Vec3::UnitX()).z() < 0.0);
}

TEST_CASE("roll is starboard down in a starboard turn", "[vehicle][trajectory]") {
  TrajectoryDesc desc = lawnmower_desc(60.0);  // first U-turn starboard, second port
  desc.attitude.roll_gain = 3.0;
  desc.attitude.roll_time_constant_s = 1.0;
  const Trajectory tr(desc);
  const double u = 2.0, r = 0.1;
  const double steady = 3.0 * std::atan(u * r / kStandardGravityMPerS2);
  CHECK(tr.roll_command(r / u) == Approx(steady));

  // first U-turn starts at t = 100 s; a quarter circle lasts 5π s ≈ 15.7 s, > 10 time constants
  const VehicleState starboard = tr.state_at(at_s(100.0 + 15.0));
  CHECK(starboard.yaw_rate == Approx(0.1));
  CHECK(starboard.pose.roll > 0.0);
  CHECK(starboard.pose.roll == Approx(steady).epsilon(1e-4));
  // R_WV of a starboard-down roll tips the body y axis (starboard) down (positive z in NED)
  CHECK((starboard.pose.R_WV() * Vec3::UnitY()).z() > 0.0);

  // second U-turn (port) starts after leg 1
  const double turn = u_turn_length_m(60.0, 20.0) / 2.0;
  const VehicleState port = tr.state_at(at_s(200.0 + turn + 15.0));
  CHECK(port.yaw_rate == Approx(-0.1));
  CHECK(port.pose.roll == Approx(-steady).epsilon(1e-4));

  // the lag: one time constant into the first turn, 1 - 1/e of the command
  CHECK(tr.state_at(at_s(101.0)).pose.roll == Approx(steady * (1.0 - std::exp(-1.0))));

  // the roll limit
  desc.attitude.roll_gain = 10.0;
  desc.attitude.max_roll = 0.1;
  const Trajectory limited(desc);
  CHECK(limited.state_at(at_s(115.0)).pose.roll == Approx(0.1).epsilon(1e-4));
}

TEST_CASE("waves rock the vehicle: roll and pitch a quarter period apart",
          "[vehicle][trajectory]") {
  // a straight line north at constant depth: no turn roll, no flight-path pitch
  TrajectoryDesc plain;
  plain.straight_length_m = 200.0;
  plain.speed_m_s = 2.0;
  plain.depth.depth_m = 15.0;
  TrajectoryDesc desc = plain;
  desc.attitude.roll_amplitude = 5.0 * kRadPerDeg;
  desc.attitude.pitch_amplitude = 3.0 * kRadPerDeg;
  desc.attitude.wave_period_s = 8.0;
  const Trajectory tr(desc);
  const Trajectory calm(plain);

  SECTION("roll = A_r·sin(2π·t/T), pitch = A_p·cos(2π·t/T)") {
    CHECK(tr.state_at(at_s(2.0)).pose.roll == Approx(5.0 * kRadPerDeg).epsilon(1e-15));
    CHECK(tr.state_at(at_s(0.0)).pose.roll == Approx(0.0).margin(1e-12));
    CHECK(tr.state_at(at_s(4.0)).pose.roll == Approx(0.0).margin(1e-12));
    CHECK(tr.state_at(at_s(6.0)).pose.roll == Approx(-5.0 * kRadPerDeg).epsilon(1e-15));
    CHECK(tr.state_at(at_s(0.0)).pose.pitch == 3.0 * kRadPerDeg);  // cos 0 = 1 exactly
    CHECK(tr.state_at(at_s(2.0)).pose.pitch == Approx(0.0).margin(1e-12));
    CHECK(tr.state_at(at_s(4.0)).pose.pitch == Approx(-3.0 * kRadPerDeg).epsilon(1e-15));
    // pitch leads roll by a quarter period
    for (double t : {0.3, 1.7, 5.2, 33.9}) {
      INFO(t);
      const double roll = tr.state_at(at_s(t)).pose.roll / (5.0 * kRadPerDeg);
      const double pitch_ahead = tr.state_at(at_s(t - 2.0)).pose.pitch / (3.0 * kRadPerDeg);
      CHECK(std::abs(roll - pitch_ahead) < 1e-12);
    }
    // the same t as the rest of the motion: also before the start and after the end (100 s)
    CHECK(tr.state_at(at_s(-2.0)).pose.roll == Approx(-5.0 * kRadPerDeg).epsilon(1e-12));
    CHECK(tr.state_at(at_s(102.0)).pose.roll == Approx(-5.0 * kRadPerDeg).epsilon(1e-12));
    CHECK(tr.state_at(at_s(104.0)).pose.pitch == Approx(3.0 * kRadPerDeg).epsilon(1e-12));
    // nothing else moves
    for (double t : {-3.0, 0.0, 2.0, 57.25, 100.0, 130.0}) {
      INFO(t);
      VehicleState a = tr.state_at(at_s(t));
      const VehicleState b = calm.state_at(at_s(t));
      a.pose.roll = b.pose.roll;
      a.pose.pitch = b.pose.pitch;
      check_same_state(a, b);
    }
    // the rates they add: at most A·ω (checked every 1 ms over two periods)
    const double omega = 2.0 * std::numbers::pi / 8.0;
    const double dt = 1e-3;
    double max_droll = 0.0, max_dpitch = 0.0;
    VehicleState previous = tr.state_at(0);
    for (int i = 1; i <= 16000; ++i) {
      const VehicleState s = tr.state_at(at_s(i * dt));
      max_droll = std::max(max_droll, std::abs(s.pose.roll - previous.pose.roll));
      max_dpitch = std::max(max_dpitch, std::abs(s.pose.pitch - previous.pose.pitch));
      previous = s;
    }
    CHECK(max_droll <= 5.0 * kRadPerDeg * omega * dt * (1.0 + 1e-6));
    CHECK(max_droll >= 5.0 * kRadPerDeg * omega * dt * 0.999);
    CHECK(max_dpitch <= 3.0 * kRadPerDeg * omega * dt * (1.0 + 1e-6));
  }

  SECTION("the sum is limited to ±max_roll and ±max_pitch") {
    TrajectoryDesc big = desc;
    big.attitude.roll_amplitude = 30.0 * kRadPerDeg;
    big.attitude.max_roll = 20.0 * kRadPerDeg;
    big.attitude.pitch_amplitude = 40.0 * kRadPerDeg;  // max_pitch 0.5 rad (28.6 degrees)
    const Trajectory limited(big);
    double max_roll = 0.0, max_pitch = 0.0;
    for (double t = -10.0; t <= 110.0; t += 0.01) {
      const VehicleState s = limited.state_at(at_s(t));
      max_roll = std::max(max_roll, std::abs(s.pose.roll));
      max_pitch = std::max(max_pitch, std::abs(s.pose.pitch));
    }
    CHECK(max_roll == 20.0 * kRadPerDeg);  // reached, never exceeded
    CHECK(max_pitch == big.attitude.max_pitch);
    CHECK(limited.state_at(at_s(2.0)).pose.roll == 20.0 * kRadPerDeg);
    CHECK(limited.state_at(at_s(6.0)).pose.roll == -20.0 * kRadPerDeg);
    // below the limit the sinusoid itself
    CHECK(limited.state_at(at_s(0.5)).pose.roll ==
          Approx(30.0 * kRadPerDeg * std::sin(std::numbers::pi / 8.0)).epsilon(1e-12));
  }

  SECTION("amplitudes 0: bit for bit the motion without waves, whatever the period") {
    // everything else on: keyhole turns, sway with yaw coupling, terrain following, roll lag
    TrajectoryDesc base = lawnmower_desc(25.0);
    base.lawnmower.first_leg_heading = 0.0;
    base.depth.mode = DepthMode::kAltitude;
    base.depth.altitude_m = 6.0;
    base.sway = {0.8, 7.0, 0.3, 0.5};
    base.attitude.roll_gain = 2.0;
    TrajectoryDesc zero = base;
    zero.attitude.roll_amplitude = 0.0;
    zero.attitude.pitch_amplitude = 0.0;
    zero.attitude.wave_period_s = 3.0;
    // one amplitude on leaves the other angle untouched
    TrajectoryDesc roll_only = base;
    roll_only.attitude.roll_amplitude = 2.0 * kRadPerDeg;
    TrajectoryDesc pitch_only = base;
    pitch_only.attitude.pitch_amplitude = 2.0 * kRadPerDeg;
    const auto seabed = sinusoid(4.0, 60.0);
    const Trajectory a(base, seabed);
    const Trajectory b(zero, seabed);
    const Trajectory r(roll_only, seabed);
    const Trajectory p(pitch_only, seabed);
    for (double t : {-5.0, 0.0, 1.234, 37.5, 101.0, 150.0, a.duration_s(), a.duration_s() + 9.0}) {
      INFO(t);
      const VehicleState sa = a.state_at(at_s(t));
      check_same_state(b.state_at(at_s(t)), sa);
      CHECK(r.state_at(at_s(t)).pose.pitch == sa.pose.pitch);
      CHECK(p.state_at(at_s(t)).pose.roll == sa.pose.roll);
    }
  }

  SECTION("out-of-range values are refused, the period whatever the amplitudes") {
    TrajectoryDesc bad = plain;
    bad.attitude.roll_amplitude = 50.0 * kRadPerDeg;
    CHECK_THROWS_WITH(Trajectory(bad), Catch::Contains("trajectory.attitude.roll_amplitude = "));
    bad = plain;
    bad.attitude.pitch_amplitude = -0.01;
    CHECK_THROWS_WITH(Trajectory(bad), Catch::Contains("trajectory.attitude.pitch_amplitude = "));
    bad = plain;
    bad.attitude.wave_period_s = 0.5;
    CHECK_THROWS_WITH(Trajectory(bad), Catch::Contains("trajectory.attitude.wave_period_s = 0.5"));
    bad.attitude.wave_period_s = 1.0;  // the bounds are allowed
    bad.attitude.roll_amplitude = std::numbers::pi / 4;
    CHECK_NOTHROW(Trajectory(bad));
  }
}

TEST_CASE("in a turn, waves rock the vehicle about its bank", "[vehicle][trajectory]") {
  TrajectoryDesc calm = lawnmower_desc(60.0);  // first U-turn (starboard) from t = 100 s
  calm.attitude.roll_gain = 3.0;
  calm.attitude.roll_time_constant_s = 1.0;
  TrajectoryDesc desc = calm;
  const double amplitude = 4.0 * kRadPerDeg;
  desc.attitude.roll_amplitude = amplitude;
  desc.attitude.wave_period_s = 8.0;
  const Trajectory tr(desc);
  const Trajectory plain(calm);
  const double steady = 3.0 * std::atan(2.0 * 0.1 / kStandardGravityMPerS2);
  // a quarter circle lasts 5π s: from 110 s on the lag has settled to within e^-10
  for (double t : {110.0, 111.0, 112.0, 113.0, 114.0, 115.5}) {
    INFO(t);
    const VehicleState s = tr.state_at(at_s(t));
    CHECK(s.yaw_rate == Approx(0.1));
    const double wave = amplitude * std::sin(2.0 * std::numbers::pi * t / 8.0);
    CHECK(s.pose.roll == Approx(steady + wave).margin(1e-5));
    // and exactly the roll without waves plus the oscillation, lag or not
    CHECK(std::abs(s.pose.roll - (plain.state_at(at_s(t)).pose.roll + wave)) < 1e-15);
  }
  // t = 114 s is 14.25 periods: the crest of the oscillation, on top of the bank
  CHECK(tr.state_at(at_s(114.0)).pose.roll == Approx(steady + amplitude).margin(1e-5));
  // during the lag too (one time constant into the turn)
  CHECK(tr.state_at(at_s(101.0)).pose.roll ==
        Approx(steady * (1.0 - std::exp(-1.0)) +
               amplitude * std::sin(2.0 * std::numbers::pi * 101.0 / 8.0))
            .epsilon(1e-9));
}

TEST_CASE("sway offsets the vehicle sideways", "[vehicle][trajectory]") {
  TrajectoryDesc desc;
  desc.start_heading = 90.0 * kRadPerDeg;  // east
  desc.speed_m_s = 2.0;
  desc.sway = {1.5, 8.0, 0.0, 0.0};
  const Trajectory crab(desc);
  const VehicleState s = crab.state_at(at_s(2.0));  // quarter period: full starboard offset
  CHECK(s.pose.position_W.y() == Approx(4.0));
  CHECK(s.pose.position_W.x() == Approx(-1.5));       // starboard of east is south
  CHECK(s.pose.yaw == Approx(90.0 * kRadPerDeg));     // pure sway: the heading stays on the path
  const VehicleState mid = crab.state_at(at_s(4.0));  // crossing back: lateral speed -A·ω
  CHECK(mid.velocity_W.x() == Approx(1.5 * 2.0 * std::numbers::pi / 8.0));
  CHECK(mid.speed_m_s == Approx(std::hypot(2.0, 1.5 * 2.0 * std::numbers::pi / 8.0)));

  desc.sway.yaw_coupling = 1.0;  // snaking: the heading follows the track
  const Trajectory snake(desc);
  const VehicleState t0 = snake.state_at(0);
  const double track = std::atan2(t0.velocity_W.y(), t0.velocity_W.x());
  CHECK(t0.pose.yaw == Approx(track));
  // the reported yaw rate is the derivative of the yaw
  for (double t : {0.7, 2.9, 5.1}) {
    const double h = 1e-4;
    const double numeric =
        wrap_to_pi(snake.state_at(at_s(t + h)).pose.yaw - snake.state_at(at_s(t - h)).pose.yaw) /
        (2 * h);
    CHECK(snake.state_at(at_s(t)).yaw_rate == Approx(numeric).margin(1e-6));
  }
}
