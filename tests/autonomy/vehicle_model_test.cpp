// The vehicle model: turn rate and vertical rate bounded, speed kept, deterministic.
#include <catch2/catch.hpp>

#include <cmath>

#include "autonomy/vehicle_model.h"

using namespace sonarloop::autonomy;

TEST_CASE("the vehicle turns no faster than its turn rate and keeps its speed") {
  VehicleParams p;
  VehicleState s;
  const VehicleCommand c{std::numbers::pi * 0.9, 0.0};  // a large turn to starboard
  const double dt = 0.05;
  for (int i = 0; i < 800; ++i) {
    const VehicleState n = step_vehicle(s, c, p, dt);
    const double turned = heading_difference_rad(n.heading_rad, s.heading_rad);
    CHECK(turned <= p.max_turn_rate_rad_s * dt + 1e-12);
    CHECK(distance_m(s.position, n.position) == Approx(p.speed_m_s * dt).epsilon(1e-9));
    s = n;
  }
  CHECK(heading_difference_rad(s.heading_rad, c.heading_rad) < 1e-9);
  // a full-rate turn takes 0.9 pi / rate seconds
  VehicleState t;
  int steps = 0;
  while (heading_difference_rad(t.heading_rad, c.heading_rad) > 1e-9 && steps < 10000) {
    t = step_vehicle(t, c, p, dt);
    ++steps;
  }
  CHECK(steps * dt == Approx(0.9 * std::numbers::pi / p.max_turn_rate_rad_s).margin(dt));
}

TEST_CASE("a full-rate circle has the turn radius") {
  VehicleParams p;
  VehicleState s;
  double min_north = 0, max_north = 0;
  for (int i = 0; i < 7000; ++i) {  // 70 s: more than one full circle
    s = step_vehicle(s, VehicleCommand{s.heading_rad + 1.0, 0.0}, p, 0.01);
    min_north = std::min(min_north, s.position.north_m);
    max_north = std::max(max_north, s.position.north_m);
  }
  CHECK(max_north - min_north == Approx(2 * p.turn_radius_m()).epsilon(0.01));
}

TEST_CASE("depth moves at the bounded vertical rate; altitude keeping") {
  VehicleParams p;
  VehicleState s;
  s.depth_m = 10.0;
  const VehicleCommand c{0.0, 12.0};
  s = step_vehicle(s, c, p, 1.0);
  CHECK(s.depth_m == Approx(10.5));
  CHECK(s.pitch_rad < 0.0);  // diving: nose down
  for (int i = 0; i < 10; ++i)
    s = step_vehicle(s, c, p, 1.0);
  CHECK(s.depth_m == Approx(12.0));
  CHECK(s.pitch_rad == 0.0);
  CHECK(depth_for_altitude(12.0, 10.0, 7.5) == Approx(14.5));
}

TEST_CASE("the model is deterministic and validates its parameters") {
  VehicleParams p;
  VehicleState a, b;
  for (int i = 0; i < 100; ++i) {
    const VehicleCommand c{0.01 * i, 5.0};
    a = step_vehicle(a, c, p, 0.1);
    b = step_vehicle(b, c, p, 0.1);
  }
  CHECK(a.position == b.position);
  CHECK(a.heading_rad == b.heading_rad);
  p.max_turn_rate_rad_s = 0.0;
  CHECK_THROWS_AS(p.validate(), std::invalid_argument);
}
