// The onboard waterfall's navigation (atr/waterfall.h): on a latitude/longitude stream without a
// frame origin, the origin is the first ping with a position fix; a ping at latitude and
// longitude 0, 0 (a recorder without a fix, as the real Iver2 recording's first ping) has none
// and keeps the last position.
#include "atr/waterfall.h"

#include <catch2/catch.hpp>
#include <vector>

#include "tests/atr/synthetic_pings.h"

using namespace sonarloop;
using namespace sonarloop::testing;

TEST_CASE("waterfall: the first ping with a fix is the origin; 0, 0 is no fix") {
  const xtf::XtfFileHeader h = make_stream_header();
  const std::vector<float> line(200, -30.0f);
  const auto ping = [&](std::uint32_t n, double north_m) {
    PingPose pose;
    pose.number = n;
    pose.north_m = north_m;
    return make_ping(h, pose, line, line, 0.1);
  };
  atr::Waterfall w;
  xtf::XtfPing no_fix = ping(0, 0.0);
  no_fix.header.sensor_y = 0.0;
  no_fix.header.sensor_x = 0.0;
  w.add(h, no_fix);
  w.add(h, ping(1, 100.0));  // the first fix: the origin
  w.add(h, ping(2, 102.0));
  xtf::XtfPing lost = ping(3, 0.0);
  lost.header.sensor_y = 0.0;
  lost.header.sensor_x = 0.0;
  w.add(h, lost);
  REQUIRE(w.size() == 4);
  REQUIRE(w.geodetic());
  CHECK(w.record(0).north_m == 0.0);  // before the first fix: at the origin it will set
  CHECK(w.record(1).north_m == Approx(0.0).margin(1e-6));
  CHECK(w.record(2).north_m == Approx(2.0).margin(1e-6));
  CHECK(w.record(3).north_m == Approx(2.0).margin(1e-6));  // no fix: the last position
  // the origin is the first fix, 100 m north of the stream's plane origin
  const GeoPoint first_fix = LocalTangentPlane(kStreamOrigin).to_geodetic(100.0, 0.0);
  CHECK(w.to_geodetic(0.0, 0.0).latitude_deg == Approx(first_fix.latitude_deg).epsilon(1e-12));
  CHECK(w.to_geodetic(0.0, 0.0).longitude_deg == Approx(first_fix.longitude_deg).epsilon(1e-12));
}
