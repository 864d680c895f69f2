#include "sim/vehicle/path.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "units/angles.h"

using namespace sonarloop;
using namespace sonarloop::vehicle;

namespace {

constexpr double kPi = std::numbers::pi;

double deg(double d) {
  return d * kPi / 180.0;
}

// Every join is C1: the end of segment i is the start of segment i + 1, position and heading.
void check_joins(const Path& path) {
  const auto& segs = path.segments();
  for (std::size_t i = 0; i + 1 < segs.size(); ++i) {
    const PathSegment& a = segs[i];
    const PathSegment& b = segs[i + 1];
    CHECK(b.s0_m == Approx(a.s0_m + a.length_m).margin(1e-9));
    const PathPoint end = path.at(b.s0_m - 1e-12);
    CHECK((end.position_NE - b.start_NE).norm() < 1e-9);
    CHECK(std::abs(a.start_heading + a.curvature_per_m * a.length_m - b.start_heading) < 1e-12);
  }
}

// Minimum distance from the path (sampled every ds) to a point.
double closest_approach(const Path& path, Vec2 point, double ds = 0.01) {
  double best = (path.at(path.length_m()).position_NE - point).norm();
  for (double s = 0.0; s <= path.length_m(); s += ds) {
    best = std::min(best, (path.at(s).position_NE - point).norm());
  }
  return best;
}

}  // namespace

TEST_CASE("a straight line and a quarter circle in closed form", "[vehicle][path]") {
  PathBuilder b({10.0, -5.0}, 0.0);
  b.line(100.0);
  b.arc(kPi / 2, 20.0);  // starboard, from north to east: centre 20 m east of the line end
  b.line(50.0);
  const Path path = b.build();
  REQUIRE(path.segments().size() == 3);
  CHECK(path.length_m() == Approx(150.0 + 10.0 * kPi));

  PathPoint p = path.at(40.0);
  CHECK(p.position_NE.x() == Approx(50.0));
  CHECK(p.position_NE.y() == Approx(-5.0));
  CHECK(p.heading == 0.0);
  CHECK(p.curvature_per_m == 0.0);

  // halfway round the arc: 45 degrees, at centre + R·(sin 45°, -cos 45°)
  p = path.at(100.0 + 5.0 * kPi);
  CHECK(p.position_NE.x() == Approx(110.0 + 20.0 * std::sin(kPi / 4)).epsilon(1e-12));
  CHECK(p.position_NE.y() == Approx(15.0 - 20.0 * std::cos(kPi / 4)).epsilon(1e-12));
  CHECK(p.heading == Approx(kPi / 4));
  CHECK(p.curvature_per_m == Approx(1.0 / 20.0));

  // end: 20 m north and 20 + 50 m east of the line end, heading east
  p = path.at(path.length_m());
  CHECK(p.position_NE.x() == Approx(130.0));
  CHECK(p.position_NE.y() == Approx(65.0));
  CHECK(p.heading == Approx(kPi / 2));

  // beyond the ends: straight run-in and run-out
  p = path.at(-10.0);
  CHECK(p.position_NE.x() == Approx(0.0).margin(1e-12));
  CHECK(p.segment == -1);
  p = path.at(path.length_m() + 10.0);
  CHECK(p.position_NE.y() == Approx(75.0));
  CHECK(p.segment == 3);
  check_joins(path);
}

TEST_CASE("fly-over passes exactly over every waypoint", "[vehicle][path]") {
  TrajectoryDesc desc;
  desc.kind = TrajectoryKind::kWaypoints;
  desc.start = {0.0, 0.0};
  desc.start_heading = deg(30.0);
  desc.speed_m_s = 2.0;
  desc.max_turn_rate_rad_s = 0.1;  // R = 20 m
  desc.waypoints = {{200.0, 0.0},   {200.0, 150.0},   {0.0, 150.0},
                    {-10.0, 165.0}, {-150.0, -100.0}, {-140.0, -100.0}};
  const Path path = plan_path(desc);
  check_joins(path);
  for (const NorthEast& w : desc.waypoints) {
    CHECK(closest_approach(path, {w.north_m, w.east_m}) < 0.006);
  }
  // the path ends on the last waypoint
  CHECK((path.at(path.length_m()).position_NE - Vec2(-140.0, -100.0)).norm() < 1e-9);
  // every arc is at the minimum radius
  for (const PathSegment& seg : path.segments()) {
    if (seg.curvature_per_m != 0.0) CHECK(std::abs(seg.curvature_per_m) == Approx(1.0 / 20.0));
  }
}

TEST_CASE("a waypoint inside the turning circle is reached by turning the other way",
          "[vehicle][path]") {
  // heading north; (5, 10) is 11.2 m from the starboard turn centre (0, 20): inside R = 20
  PathBuilder b({0.0, 0.0}, 0.0);
  b.fly_over({5.0, 10.0}, 20.0);
  const Path path = b.build();
  REQUIRE(path.segments().size() == 2);
  const PathSegment& turn = path.segments()[0];
  CHECK(turn.curvature_per_m < 0.0);                 // port
  CHECK(turn.length_m / 20.0 > kPi);                 // a loop of more than half a circle
  CHECK(path.segments()[1].curvature_per_m == 0.0);  // then straight at it
  CHECK((path.at(path.length_m()).position_NE - Vec2(5.0, 10.0)).norm() < 1e-9);

  // dead astern: turned for to starboard
  PathBuilder astern({0.0, 0.0}, 0.0);
  astern.fly_over({-100.0, 0.0}, 20.0);
  const Path back = astern.build();
  CHECK(back.segments()[0].curvature_per_m > 0.0);
  CHECK((back.at(back.length_m()).position_NE - Vec2(-100.0, 0.0)).norm() < 1e-9);

  // dead ahead: one straight line, no turn
  PathBuilder ahead({0.0, 0.0}, deg(45.0));
  ahead.fly_over({100.0, 100.0}, 20.0);
  REQUIRE(ahead.build().segments().size() == 1);
  CHECK(ahead.build().length_m() == Approx(100.0 * std::sqrt(2.0)));
}

TEST_CASE("lawnmower legs, spacing and regular U-turns", "[vehicle][path]") {
  TrajectoryDesc desc;
  desc.kind = TrajectoryKind::kLawnmower;
  desc.speed_m_s = 2.0;
  desc.max_turn_rate_rad_s = 0.1;  // R = 20 m
  LawnmowerDesc& m = desc.lawnmower;
  m.origin = {1000.0, -500.0};
  m.first_leg_heading = deg(60.0);
  m.leg_length_m = 300.0;
  m.line_spacing_m = 70.0;  // >= 2R: quarter, 30 m across, quarter
  m.legs = 5;
  m.first_turn = TurnDirection::kStarboard;
  const Path path = plan_path(desc);
  check_joins(path);

  const double radius = 20.0;
  const double turn_length = kPi * radius + 70.0 - 2.0 * radius;
  CHECK(u_turn_length_m(70.0, radius) == Approx(turn_length));
  CHECK(path.length_m() == Approx(5 * 300.0 + 4 * turn_length));

  const Vec2 origin(1000.0, -500.0);
  const Vec2 along = heading_vector(m.first_leg_heading);
  const Vec2 across(-along.y(), along.x());  // starboard of the first leg
  int legs = 0;
  for (const PathSegment& seg : path.segments()) {
    if (seg.leg < 0) continue;
    const int i = seg.leg;
    CHECK(i == legs);
    ++legs;
    CHECK(seg.length_m == Approx(300.0));
    CHECK(seg.curvature_per_m == 0.0);
    // leg i lies i·spacing to starboard; even legs run along, odd legs back
    const Vec2 rel = seg.start_NE - origin;
    CHECK(rel.dot(across) == Approx(70.0 * i).margin(1e-9));
    CHECK(rel.dot(along) == Approx(i % 2 == 0 ? 0.0 : 300.0).margin(1e-9));
    CHECK(wrap_to_pi(seg.start_heading - m.first_leg_heading - (i % 2) * kPi) ==
          Approx(0.0).margin(1e-12));
  }
  CHECK(legs == 5);

  // the turns reach R beyond the leg ends and stay between the legs
  double max_along = -1e300, min_along = 1e300, min_across = 1e300, max_across = -1e300;
  for (double s = 0.0; s <= path.length_m(); s += 0.05) {
    const Vec2 rel = path.at(s).position_NE - origin;
    max_along = std::max(max_along, rel.dot(along));
    min_along = std::min(min_along, rel.dot(along));
    min_across = std::min(min_across, rel.dot(across));
    max_across = std::max(max_across, rel.dot(across));
  }
  CHECK(max_along == Approx(300.0 + radius).margin(1e-4));
  CHECK(min_along == Approx(-radius).margin(1e-4));
  CHECK(min_across == Approx(0.0).margin(1e-9));
  CHECK(max_across == Approx(4 * 70.0).margin(1e-9));
}

TEST_CASE("lawnmower with spacing below 2R flies keyhole turns", "[vehicle][path]") {
  TrajectoryDesc desc;
  desc.kind = TrajectoryKind::kLawnmower;
  desc.speed_m_s = 2.0;
  desc.max_turn_rate_rad_s = 0.1;  // R = 20 m
  LawnmowerDesc& m = desc.lawnmower;
  m.origin = {0.0, 0.0};
  m.first_leg_heading = 0.0;
  m.leg_length_m = 100.0;
  m.line_spacing_m = 25.0;
  m.legs = 3;
  m.first_turn = TurnDirection::kPort;  // survey progresses west
  const Path path = plan_path(desc);
  check_joins(path);

  const double radius = 20.0;
  const double alpha = std::acos((radius + 12.5) / (2.0 * radius));
  CHECK(keyhole_angle(25.0, radius) == Approx(alpha));
  CHECK(alpha == Approx(0.62236).epsilon(1e-4));
  CHECK(u_turn_length_m(25.0, radius) == Approx(radius * (kPi + 4.0 * alpha)));
  CHECK(path.length_m() == Approx(300.0 + 2.0 * radius * (kPi + 4.0 * alpha)));

  // legs: (0,0) north, (100, -25) south, (0, -50) north
  const Vec2 starts[] = {{0.0, 0.0}, {100.0, -25.0}, {0.0, -50.0}};
  int legs = 0;
  for (const PathSegment& seg : path.segments()) {
    if (seg.leg < 0) continue;
    CHECK((seg.start_NE - starts[seg.leg]).norm() < 1e-9);
    CHECK(seg.length_m == Approx(100.0));
    ++legs;
  }
  CHECK(legs == 3);
  // arcs only, all at radius R, first away from the survey side (starboard here)
  int arcs = 0;
  for (const PathSegment& seg : path.segments()) {
    if (seg.leg >= 0) continue;
    CHECK(std::abs(seg.curvature_per_m) == Approx(1.0 / radius));
    ++arcs;
  }
  CHECK(arcs == 6);
  CHECK(path.segments()[1].curvature_per_m > 0.0);

  // extent of the first turn: R(1 + 2 sin α) beyond the leg end, R - d/2 outside each leg (the
  // first arc only reaches R(1 - cos α) outside, the middle arc bulges further)
  double max_north = -1e300, max_east = -1e300, min_east = 1e300;
  const double turn_end = path.segments()[4].s0_m;  // leg 1 starts after three arcs
  for (double s = 100.0; s <= turn_end; s += 0.01) {
    const Vec2 p = path.at(s).position_NE;
    max_north = std::max(max_north, p.x());
    max_east = std::max(max_east, p.y());
    min_east = std::min(min_east, p.y());
  }
  CHECK(max_north == Approx(100.0 + u_turn_overshoot_m(25.0, radius)).margin(1e-5));
  CHECK(u_turn_overshoot_m(25.0, radius) == Approx(radius * (1.0 + 2.0 * std::sin(alpha))));
  CHECK(max_east == Approx(radius - 12.5).margin(1e-6));
  CHECK(min_east == Approx(-25.0 - (radius - 12.5)).margin(1e-6));
  const PathPoint first_arc_end = path.at(path.segments()[2].s0_m);
  CHECK(first_arc_end.position_NE.y() == Approx(radius * (1.0 - std::cos(alpha))));
  CHECK(first_arc_end.position_NE.x() == Approx(100.0 + radius * std::sin(alpha)));
}

TEST_CASE("the keyhole turn tends to the semicircle as spacing reaches 2R", "[vehicle][path]") {
  const double radius = 10.0;
  CHECK(keyhole_angle(20.0, radius) == 0.0);
  CHECK(keyhole_angle(20.0 - 1e-9, radius) < 1e-3);
  CHECK(u_turn_length_m(20.0 - 1e-9, radius) == Approx(kPi * radius).epsilon(1e-4));
  CHECK(u_turn_length_m(20.0, radius) == Approx(kPi * radius));
  // spacing -> 0: α -> 60 degrees, length 7πR/3
  CHECK(keyhole_angle(1e-9, radius) == Approx(kPi / 3));
  CHECK(u_turn_length_m(1e-9, radius) == Approx(7.0 * kPi * radius / 3.0));
}
