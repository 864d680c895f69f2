// The external pose at a simulation time (emulator/external_pose.h), the one sequence pings and
// navigation frames follow: the source asked for the pose of the pacer's wall time less the
// delay, nothing before the first pose or past stale_after, the parts the source sends over the
// trajectory's state and the trajectory for the rest, an error-free navigation model.
#include "emulator/external_pose.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "tests/emulator/simulated_clock.h"

using namespace sonarloop;
using namespace sonarloop::emulator;

namespace {

// A source that returns a set pose and records what it was asked.
class FakeSource final : public PoseSource {
 public:
  std::optional<ExternalPose> pose;
  bool extrapolate = false;
  mutable std::vector<std::int64_t> asked_tau, asked_max;
  std::optional<ExternalPose> latest() const override { return pose; }
  std::optional<ExternalPose> pose_at(std::int64_t tau_ns, std::int64_t max_extrapolation_ns,
                                      bool* extrapolated) const override {
    asked_tau.push_back(tau_ns);
    asked_max.push_back(max_extrapolation_ns);
    if (extrapolated) *extrapolated = extrapolate;
    return pose;
  }
  std::string describe() const override { return "fake"; }
  PoseSourceStats stats() const override { return {}; }
};

vehicle::TrajectoryDesc straight_north() {
  vehicle::TrajectoryDesc d;
  d.kind = vehicle::TrajectoryKind::kStraight;
  d.start = {0.0, 0.0};
  d.start_heading = 0.0;
  d.speed_m_s = 2.0;
  return d;
}

}  // namespace

TEST_CASE("external pose: asked at the wall time less the delay; none before the first pose") {
  testing::SimulatedClock clock;
  Pacer pacer(clock, Rate{false, 2.0});  // twice real time
  pacer.start_at(1'000'000'000);
  const vehicle::Trajectory trajectory(straight_north());
  FakeSource source;
  const ExternalPoseInput in(source, pacer, clock, trajectory, 100'000'000, 2'000'000'000, 7);
  const ExternalPoseInput::Reading none = in.read(4'000'000'000);
  CHECK_FALSE(none.state);
  CHECK(none.age_ns == -1);
  REQUIRE(source.asked_tau.size() == 1);
  // wall of t = 4 s at twice real time: 1 s + 2 s; less the 0.1 s delay
  CHECK(source.asked_tau[0] == std::int64_t{1'000'000'000} + 2'000'000'000 - 100'000'000);
  CHECK(source.asked_max[0] == 2'000'000'000);  // extrapolated for at most stale_after
}

TEST_CASE("external pose: the parts the source sends over the trajectory's state, fresh only") {
  testing::SimulatedClock clock;
  Pacer pacer(clock, Rate{false, 1.0});
  pacer.start_at(0);
  const vehicle::Trajectory trajectory(straight_north());
  FakeSource source;
  ExternalPose p;
  p.received_ns = 0;
  p.pose.position_W = Vec3(10.0, 20.0, 30.0);
  p.pose.yaw = 1.0;
  p.pose.pitch = 0.1;
  p.pose.roll = 0.2;
  p.has_position = true;
  p.has_heading = true;  // no depth, no attitude
  p.altitude_m = 7.5;
  source.pose = p;
  source.extrapolate = true;
  const ExternalPoseInput in(source, pacer, clock, trajectory, 0, 2'000'000'000, 7);
  clock.advance(1'500'000'000);  // the pose is 1.5 s old: fresh
  const SimTime t = 1'000'000'000;
  const ExternalPoseInput::Reading r = in.read(t);
  REQUIRE(r.state);
  CHECK(r.age_ns == 1'500'000'000);
  CHECK(r.extrapolated);
  const vehicle::VehicleState traj = trajectory.state_at(t);
  CHECK(r.state->pose.position_W.x() == 10.0);
  CHECK(r.state->pose.position_W.y() == 20.0);
  CHECK(r.state->pose.position_W.z() == traj.pose.position_W.z());  // depth: the trajectory's
  CHECK(r.state->pose.yaw == 1.0);
  CHECK(r.state->pose.pitch == traj.pose.pitch);  // attitude: the trajectory's
  CHECK(r.state->pose.roll == traj.pose.roll);
  CHECK(r.state->altitude_m == 7.5);
  // the navigation model adds no error: it reports the merged pose as it is
  const vehicle::NavSolution nav = in.navigation().measure(*r.state);
  CHECK(nav.north_m == Approx(10.0).margin(1e-9));
  CHECK(nav.east_m == Approx(20.0).margin(1e-9));
  CHECK(nav.heading == Approx(1.0).margin(1e-12));

  clock.advance(1'000'000'000);  // 2.5 s old: past stale_after
  const ExternalPoseInput::Reading stale = in.read(t);
  CHECK_FALSE(stale.state);
  CHECK(stale.age_ns == 2'500'000'000);
}
