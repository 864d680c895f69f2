#pragma once
// The external pose (`run --pose-from`, hardware in the loop) at a simulation time: the one
// sequence that the sonar's pings (ping_producer.h) and the navigation frames (the publisher,
// emulator_loop.cpp) both follow.
//
//   1. The pose of the sample's own time less the delay: PoseSource::pose_at(τ) at
//      τ = the pacer's wall time of t − delay (interpolated between the source's samples, or
//      extrapolated after the last, emulator/pose_history.h).
//   2. Fresh or not: no pose yet, or one whose newest sample arrived more than stale_after ago,
//      gives none (the caller then emits no ping, or withholds the frames that depend on it).
//   3. Merged into the trajectory's state at t (merge_external_pose): what the source does not
//      send (its has_* flags; velocity and yaw rate always) comes from the trajectory.
//   4. Measured by an error-free navigation model: the external pose is the vehicle's own
//      navigation, published and recorded as it is.
#include <cstdint>
#include <optional>

#include "emulator/pacer.h"
#include "emulator/pose_source.h"
#include "sim/vehicle/nav_sensor.h"
#include "sim/vehicle/trajectory.h"

namespace sonarloop::emulator {

// The state rendered and published with --pose-from: the trajectory's state at the same time
// with every part the external pose provides (its has_* flags) replaced by it, and its altitude.
vehicle::VehicleState merge_external_pose(vehicle::VehicleState state, const ExternalPose& pose);

class ExternalPoseInput {
 public:
  // Every reference must outlive this object. seed: the navigation model's (it adds no errors).
  ExternalPoseInput(const PoseSource& source, const Pacer& pacer, const Clock& clock,
                    const vehicle::Trajectory& trajectory, SimTime delay_ns, SimTime stale_after_ns,
                    std::uint64_t seed);

  struct Reading {
    std::optional<vehicle::VehicleState> state;  // none: no fresh pose (steps 1-2)
    std::int64_t age_ns = -1;   // now less the pose's newest arrival; -1: no pose yet
    bool extrapolated = false;  // the position was extrapolated past the last sample
  };
  // Steps 1-3 for simulation time t. Thread-safe (the source is; the rest is read only).
  Reading read(SimTime t) const;
  // Step 4: the error-free navigation model.
  const vehicle::NavSensorModel& navigation() const { return navigation_; }

  SimTime stale_after_ns() const { return stale_after_ns_; }
  const PoseSource& source() const { return source_; }

 private:
  const PoseSource& source_;
  const Pacer& pacer_;
  const Clock& clock_;
  const vehicle::Trajectory& trajectory_;
  SimTime delay_ns_;
  SimTime stale_after_ns_;
  vehicle::NavSensorModel navigation_;
};

}  // namespace sonarloop::emulator
