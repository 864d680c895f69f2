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

TEST_CASE("straight line: position and heading at known times", "[vehicle][trajectory]") {
  TrajectoryDesc desc;
  desc.kind = TrajectoryKind::kStraight;
  desc.start = {100.0, -50.0};
  desc.start_heading = 30.0 * kRadPerDeg;
  desc.straight_length_m = 500.0;
  desc.speed_m_s = 2.0;
  desc.depth.depth_m = 15.0;
  const Trajectory tr(desc);
  CHECK(tr.duration_s() == Approx(250.0));
  CHECK(tr.length_m() == Approx(500.0));

  const VehicleState s = tr.state_at(at_s(10.0));
  CHECK(s.t == at_s(10.0));
  CHECK(s.pose.position_W.x() == Approx(100.0 + 20.0 * std::cos(30.0 * kRadPerDeg)).epsilon(1e-12));
  CHECK(s.pose.position_W.y() == Approx(-50.0 + 20.0 * std::sin(30.0 * kRadPerDeg)).epsilon(1e-12));
  CHECK(s.pose.position_W.z() == 15.0);
  CHECK(s.pose.yaw == Approx(30.0 * kRadPerDeg).epsilon(1e-14));
  CHECK(s.pose.pitch == 0.0);
  CHECK(s.pose.roll == 0.0);
  CHECK(s.velocity_W.x() == Approx(2.0 * std::cos(30.0 * kRadPerDeg)));
  CHECK(s.velocity_W.y() == Approx(2.0 * std::sin(30.0 * kRadPerDeg)));
  CHECK(s.velocity_W.z() == 0.0);
  CHECK(s.speed_m_s == Approx(2.0));
  CHECK(s.yaw_rate == 0.0);
  CHECK(std::isnan(s.altitude_m));  // no seabed given
  CHECK(s.path_s_m == Approx(20.0));
  CHECK(s.leg == -1);

  const VehicleState end = tr.state_at(at_s(250.0));
  CHECK(end.pose.position_W.x() == Approx(100.0 + 500.0 * std::cos(30.0 * kRadPerDeg)));
  // past the end the vehicle keeps going straight
  const VehicleState after = tr.state_at(at_s(260.0));
  CHECK(after.pose.position_W.y() == Approx(-50.0 + 520.0 * std::sin(30.0 * kRadPerDeg)));
  CHECK(after.pose.yaw == Approx(30.0 * kRadPerDeg));

  // with a seabed, the altitude is known along the path
  const Trajectory over(desc, [](double, double) { return 40.0; });
  CHECK(over.state_at(at_s(100.0)).altitude_m == Approx(25.0));
  CHECK(std::isnan(over.state_at(at_s(251.0)).altitude_m));
  CHECK(over.min_altitude_m() == Approx(25.0));
}

TEST_CASE("waypoints are passed and the turn rate never exceeds the bound",
          "[vehicle][trajectory]") {
  TrajectoryDesc desc;
  desc.kind = TrajectoryKind::kWaypoints;
  desc.start = {0.0, 0.0};
  desc.start_heading = -40.0 * kRadPerDeg;
  desc.speed_m_s = 1.5;
  desc.max_turn_rate_rad_s = 0.08;  // R = 18.75 m
  desc.waypoints = {{150.0, 20.0}, {160.0, 160.0}, {20.0, 150.0}, {30.0, 140.0}, {-80.0, -60.0}};
  const Trajectory tr(desc);
  CHECK(tr.turn_radius_m() == Approx(18.75));

  const double dt = 0.01;
  const auto states = sample(tr, dt);
  // each waypoint, in order, passed within 1 cm (fly-over passes over it; tolerance = sampling)
  std::size_t from = 0;
  for (const NorthEast& w : desc.waypoints) {
    double best = 1e300;
    std::size_t best_i = from;
    for (std::size_t i = from; i < states.size(); ++i) {
      const double d = std::hypot(states[i].pose.position_W.x() - w.north_m,
                                  states[i].pose.position_W.y() - w.east_m);
      if (d < best) {
        best = d;
        best_i = i;
      }
    }
    CHECK(best < 0.01);
    CHECK(best < tr.turn_radius_m());
    from = best_i;
  }
  // turn rate from the yaw sampled every 10 ms, and as reported
  double max_rate = 0.0;
  for (std::size_t i = 1; i < states.size(); ++i) {
    const double rate = std::abs(wrap_to_pi(states[i].pose.yaw - states[i - 1].pose.yaw)) / dt;
    max_rate = std::max(max_rate, rate);
    CHECK(std::abs(states[i].yaw_rate) <= desc.max_turn_rate_rad_s * (1.0 + 1e-12));
  }
  CHECK(max_rate <= desc.max_turn_rate_rad_s * (1.0 + 1e-6));
  CHECK(max_rate >= desc.max_turn_rate_rad_s * 0.999);  // it does turn at the bound
  std::printf("waypoints: numerical max turn rate %.6f rad/s (bound %.6f)\n", max_rate,
              desc.max_turn_rate_rad_s);
}

TEST_CASE("lawnmower legs, spacing, lengths and U-turn timing", "[vehicle][trajectory]") {
  for (const double spacing : {60.0, 25.0}) {  // regular U-turn, keyhole
    const TrajectoryDesc desc = lawnmower_desc(spacing);
    const Trajectory tr(desc);
    const double radius = 20.0;
    const double turn = u_turn_length_m(spacing, radius);
    CHECK(tr.duration_s() == Approx((4 * 200.0 + 3 * turn) / 2.0));

    const Vec2 along = heading_vector(20.0 * kRadPerDeg);
    const Vec2 across(-along.y(), along.x());
    const double dt = 0.05;
    const auto states = sample(tr, dt);
    // per leg: time on the leg, lateral offset, heading
    std::vector<double> leg_time(4, 0.0);
    double max_rate = 0.0;
    for (std::size_t i = 0; i < states.size(); ++i) {
      const VehicleState& s = states[i];
      if (i > 0) {
        max_rate =
            std::max(max_rate, std::abs(wrap_to_pi(s.pose.yaw - states[i - 1].pose.yaw)) / dt);
      }
      if (s.leg < 0) continue;
      leg_time[static_cast<std::size_t>(s.leg)] += dt;
      const Vec2 p(s.pose.position_W.x(), s.pose.position_W.y());
      CHECK(p.dot(across) == Approx(spacing * s.leg).margin(1e-9));
      CHECK(p.dot(along) >= -1e-9);
      CHECK(p.dot(along) <= 200.0 + 1e-9);
      CHECK(wrap_to_pi(s.pose.yaw - 20.0 * kRadPerDeg - (s.leg % 2) * std::numbers::pi) ==
            Approx(0.0).margin(1e-12));
    }
    for (double t : leg_time)
      CHECK(t == Approx(100.0).margin(dt * 1.01));  // 200 m at 2 m/s
    CHECK(max_rate <= 0.1 * (1.0 + 1e-6));

    // the first U-turn: from the end of leg 0 to the start of leg 1
    const VehicleState leg0_end = tr.state_at(at_s(100.0));
    const VehicleState leg1_start = tr.state_at(at_s(100.0 + turn / 2.0));
    // (at a join the state belongs to the later segment)
    CHECK(tr.state_at(at_s(100.0 - 1e-3)).leg == 0);
    CHECK(leg0_end.leg == -1);
    CHECK(tr.state_at(at_s(100.0 + turn / 2.0 + 1e-3)).leg == 1);
    const Vec2 a(leg0_end.pose.position_W.x(), leg0_end.pose.position_W.y());
    const Vec2 b(leg1_start.pose.position_W.x(), leg1_start.pose.position_W.y());
    CHECK((b - a).dot(across) == Approx(spacing));
    CHECK((b - a).dot(along) == Approx(0.0).margin(1e-9));
    CHECK(tr.state_at(at_s(100.0 + turn / 4.0)).leg == -1);
  }
}

TEST_CASE("speed is constant along the path", "[vehicle][trajectory]") {
  for (const double spacing : {60.0, 25.0}) {
    const Trajectory tr(lawnmower_desc(spacing));
    const double dt = 0.1;
    const auto states = sample(tr, dt);
    for (std::size_t i = 0; i < states.size(); ++i) {
      CHECK(states[i].speed_m_s == Approx(2.0).epsilon(1e-12));
      CHECK(states[i].velocity_W.head<2>().norm() == Approx(2.0).epsilon(1e-12));
      if (i == 0) continue;
      // chord / time: 2 m/s up to the arc's chord shortening sin(x)/x, x = r·dt/2
      const double chord = (states[i].pose.position_W - states[i - 1].pose.position_W).norm() / dt;
      CHECK(chord == Approx(2.0).epsilon(1e-5));
    }
  }
}

TEST_CASE("terrain following over a sinusoidal seabed", "[vehicle][trajectory]") {
  SECTION("a seabed the vehicle can follow: altitude held") {
    // 3 m amplitude, 100 m wavelength at 2 m/s: seabed vertical rate up to 0.377 m/s < 0.5
    const Trajectory tr(altitude_line(8.0, 50.0), sinusoid(3.0, 100.0));
    const double dt = 0.05;
    const auto states = sample(tr, dt);
    double lo = 1e300, hi = -1e300, max_w = 0.0;
    for (std::size_t i = 0; i < states.size(); ++i) {
      const VehicleState& s = states[i];
      lo = std::min(lo, s.altitude_m);
      hi = std::max(hi, s.altitude_m);
      max_w = std::max(max_w, std::abs(s.velocity_W.z()));
      // altitude as stated equals the seabed below minus the depth
      CHECK(s.altitude_m ==
            Approx(30.0 + 3.0 * std::sin(2.0 * std::numbers::pi * s.pose.position_W.x() / 100.0) -
                   s.pose.position_W.z())
                .margin(2e-3));
    }
    std::printf("terrain following (feasible): altitude in [%.4f, %.4f] m, max |w| %.4f m/s\n", lo,
                hi, max_w);
    // the seabed's curvature is at most 3·(2π/100)² = 0.0118 /m: departure ~ κW²/24 = 0.012 m
    CHECK(lo >= 8.0 - 0.02);
    CHECK(hi <= 8.0 + 0.02);
    CHECK(max_w <= 0.5 + 1e-12);
    CHECK(max_w >= 0.3);  // it does follow the seabed
  }

  SECTION("a seabed too steep to follow: altitude held above the command, rate bounded") {
    // 10 m amplitude, 80 m wavelength: seabed rate up to 1.57 m/s, three times the bound
    const Trajectory tr(altitude_line(8.0, 200.0), sinusoid(10.0, 80.0));
    const double dt = 0.05;
    const auto states = sample(tr, dt);
    double lo = 1e300, max_w = 0.0, max_w_numeric = 0.0;
    for (std::size_t i = 0; i < states.size(); ++i) {
      lo = std::min(lo, states[i].altitude_m);
      max_w = std::max(max_w, std::abs(states[i].velocity_W.z()));
      if (i > 0) {
        max_w_numeric = std::max(
            max_w_numeric,
            std::abs(states[i].pose.position_W.z() - states[i - 1].pose.position_W.z()) / dt);
      }
    }
    std::printf(
        "terrain following (steep, look-ahead 200 m): min altitude %.4f m, max |w| %.4f "
        "(numerical %.4f) m/s\n",
        lo, max_w, max_w_numeric);
    // the knots never go below 8 m; the smoothing dips below them by at most
    // w_max·W/(4u) = 0.3125 m where a climb turns into a dive over a crest
    CHECK(lo >= 8.0 - 0.3125 - 2e-3);  // (the seabed is sampled every 0.5 m and interpolated)
    CHECK(tr.min_altitude_m() >= 8.0 - 0.3125 - 1e-9);
    CHECK(max_w <= 0.5 + 1e-12);
    CHECK(max_w_numeric <= 0.5 + 1e-9);
    CHECK(max_w == Approx(0.5).margin(1e-3));  // it climbs and dives at the bound

    // the same seabed seen only 5 m ahead: the climb starts too late, reported
    const Trajectory late(altitude_line(8.0, 5.0), sinusoid(10.0, 80.0));
    std::printf("terrain following (steep, look-ahead 5 m): min altitude %.4f m\n",
                late.min_altitude_m());
    CHECK(late.min_altitude_m() < 6.0);
    double late_w = 0.0;
    for (const auto& s : sample(late, 0.05))
      late_w = std::max(late_w, std::abs(s.velocity_W.z()));
    CHECK(late_w <= 0.5 + 1e-12);
  }
}

TEST_CASE("position and attitude are continuous", "[vehicle][trajectory]") {
  // everything on: keyhole turns, sway with yaw coupling, terrain following, roll lag
  TrajectoryDesc desc = lawnmower_desc(25.0);
  desc.lawnmower.first_leg_heading = 0.0;  // legs run north over the sinusoid
  desc.depth.mode = DepthMode::kAltitude;
  desc.depth.altitude_m = 6.0;
  desc.sway = {0.8, 7.0, 0.3, 0.5};
  desc.attitude.roll_gain = 2.0;
  const Trajectory tr(desc, sinusoid(4.0, 60.0));

  // bounds on the rates of change: speed with sway, turn rate + sway yaw rate, pitch rate from
  // the vertical acceleration bound, roll rate from the lag
  const double omega = 2.0 * std::numbers::pi / 7.0;
  const double max_speed = std::hypot(2.0 + 0.1 * 0.8 + 0.8 * omega, 0.5);
  const double max_yaw_rate = 0.1 + 0.5 * 0.8 * omega * omega / 2.0;
  const double max_pitch_rate = 2.0 * 2.0 * 0.5 / 5.0 / 2.0;
  const double max_roll_rate = 2.0 * desc.attitude.max_roll / desc.attitude.roll_time_constant_s;

  const double dt = 1e-3;
  VehicleState previous = tr.state_at(0);
  double max_dp = 0.0, max_dyaw = 0.0, max_dpitch = 0.0, max_droll = 0.0;
  const auto n = static_cast<long>(tr.duration_s() / dt);
  for (long i = 1; i <= n; ++i) {
    const VehicleState s = tr.state_at(at_s(static_cast<double>(i) * dt));
    max_dp = std::max(max_dp, (s.pose.position_W - previous.pose.position_W).norm());
    max_dyaw = std::max(max_dyaw, std::abs(wrap_to_pi(s.pose.yaw - previous.pose.yaw)));
    max_dpitch = std::max(max_dpitch, std::abs(s.pose.pitch - previous.pose.pitch));
    max_droll = std::max(max_droll, std::abs(s.pose.roll - previous.pose.roll));
    previous = s;
  }
  std::printf("continuity over 1 ms: |dp| %.3g m, |dyaw| %.3g, |dpitch| %.3g, |droll| %.3g rad\n",
              max_dp, max_dyaw, max_dpitch, max_droll);
  CHECK(max_dp <= max_speed * 1.05 * dt);
  CHECK(max_dyaw <= max_yaw_rate * 1.001 * dt);
  CHECK(max_dpitch <= max_pitch_rate * 1.05 * dt);
  CHECK(max_droll <= max_roll_rate * dt);

  // at every segment join, states 1 µs apart differ by about nothing
  for (const PathSegment& seg : tr.path().segments()) {
    const double t = seg.s0_m / 2.0;
    const VehicleState a = tr.state_at(at_s(t - 1e-6));
    const VehicleState b = tr.state_at(at_s(t + 1e-6));
    CHECK((a.pose.position_W - b.pose.position_W).norm() < 1e-5);
    CHECK(std::abs(wrap_to_pi(a.pose.yaw - b.pose.yaw)) < 1e-6);
    CHECK(std::abs(a.pose.pitch - b.pose.pitch) < 1e-6);
    CHECK(std::abs(a.pose.roll - b.pose.roll) < 1e-6);
  }
}

TEST_CASE("state_at is a pure function of time", "[vehicle][trajectory]") {
  TrajectoryDesc desc = lawnmower_desc(25.0);
  desc.depth.mode = DepthMode::kAltitude;
  desc.sway = {0.5, 9.0, 0.0, 0.3};
  const Trajectory tr(desc, sinusoid(2.0, 70.0));
  const SimTime t = at_s(123.456);
  const VehicleState a = tr.state_at(t);
  for (int i = 0; i < 100; ++i)
    (void)tr.state_at(at_s(i * 7.1));
  const VehicleState b = tr.state_at(t);
  CHECK(a.pose.position_W == b.pose.position_W);
  CHECK(a.pose.yaw == b.pose.yaw);
  CHECK(a.pose.roll == b.pose.roll);
  CHECK(a.pose.pitch == b.pose.pitch);
  // and an identical trajectory built again gives identical states
  const Trajectory again(desc, sinusoid(2.0, 70.0));
  const VehicleState c = again.state_at(t);
  CHECK(a.pose.position_W == c.pose.position_W);
  CHECK(a.altitude_m == c.altitude_m);
}

TEST_CASE("bad descriptions are refused with a clear message", "[vehicle][trajectory]") {
  TrajectoryDesc desc;
  desc.speed_m_s = 0.0;
  CHECK_THROWS_WITH(Trajectory(desc), Catch::Contains("trajectory.speed_m_s = 0"));

  TrajectoryDesc altitude;
  altitude.depth.mode = DepthMode::kAltitude;
  CHECK_THROWS_WITH(Trajectory(altitude), Catch::Contains("needs the seabed depth"));
  CHECK_THROWS_WITH(Trajectory(altitude, [](double, double) { return std::nan(""); }),
                    Catch::Contains("the seabed depth at (north -3, east 0) m, -3 m along "
                                    "the path, is nan: must be finite"));

  TrajectoryDesc longest;
  longest.straight_length_m = 1e9;
  CHECK_THROWS_WITH(Trajectory(longest), Catch::Contains("raise profile_step_m"));
}
