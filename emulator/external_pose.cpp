#include "emulator/external_pose.h"

namespace sonarloop::emulator {

vehicle::VehicleState merge_external_pose(vehicle::VehicleState state, const ExternalPose& pose) {
  if (pose.has_position) {
    state.pose.position_W.x() = pose.pose.position_W.x();
    state.pose.position_W.y() = pose.pose.position_W.y();
  }
  if (pose.has_depth) state.pose.position_W.z() = pose.pose.position_W.z();
  if (pose.has_heading) state.pose.yaw = pose.pose.yaw;
  if (pose.has_attitude) {
    state.pose.pitch = pose.pose.pitch;
    state.pose.roll = pose.pose.roll;
  }
  state.altitude_m = pose.altitude_m;
  return state;
}

ExternalPoseInput::ExternalPoseInput(const PoseSource& source, const Pacer& pacer,
                                     const Clock& clock, const vehicle::Trajectory& trajectory,
                                     SimTime delay_ns, SimTime stale_after_ns, std::uint64_t seed)
    : source_(source),
      pacer_(pacer),
      clock_(clock),
      trajectory_(trajectory),
      delay_ns_(delay_ns),
      stale_after_ns_(stale_after_ns),
      navigation_(vehicle::NavNoiseDesc{}, seed) {}

ExternalPoseInput::Reading ExternalPoseInput::read(SimTime t) const {
  Reading r;
  const std::int64_t now = clock_.now_ns();
  const std::optional<ExternalPose> ext =
      source_.pose_at(pacer_.wall_of(t) - delay_ns_, stale_after_ns_, &r.extrapolated);
  r.age_ns = ext ? now - ext->received_ns : -1;
  if (!ext || r.age_ns > stale_after_ns_) return r;
  r.state = merge_external_pose(trajectory_.state_at(t), *ext);
  return r;
}

}  // namespace sonarloop::emulator
