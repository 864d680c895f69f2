#pragma once
// What a render worker does for ping k (RenderQueue's PingProducer): the pose at the ping time,
// the render, the navigation the sonar records, and the XTF packet.
//
// Ping time t_k = k·ping_period (ns since the mission start), UTC = epoch + t_k. Two pose modes:
//
// Trajectory (default). The true pose is Trajectory::state_at(t_k); the XTF ping's navigation
// fields come from NavSensorModel::measure(state) (what the vehicle's navigation reports, with
// the scenario's errors), the render from the true pose, with randomness keyed by (seed, k).
// The ping is therefore a pure function of (scenario, k): workers may render it any time ahead,
// on any thread. After handing ping k to the publisher a worker prepares ping
// k + prepare_ahead_pings() (work_ahead; PingRenderer::prepare: the heightmap tiles along its
// ground lines, or the ray tracer's view), so the scene is made ahead of the pings on the
// workers themselves, off the path of the ping due now, and a ping rarely waits for it.
//
// External pose (--pose-from). The worker waits for the ping's wall time, takes the source's
// latest pose and renders from it. Fields the source does not provide (its has_* flags) come
// from the trajectory at t_k: position (north, east), depth, heading, pitch and roll; velocity
// and yaw rate always do (no external source sends them). A pose older than stale_after (or none
// yet) gives no ping (slot.emitted = false). The navigation recorded in the XTF ping is that
// pose without added errors (it is the vehicle's own navigation). Poses are not known ahead:
// what a ping reads is made when it is rendered.
#include <atomic>
#include <cstdint>
#include <vector>

#include "common/geodesy.h"
#include "drivers/xtf/xtf_types.h"
#include "emulator/pacer.h"
#include "emulator/pose_source.h"
#include "emulator/render_queue.h"
#include "sim/render/ping_renderer.h"
#include "sim/vehicle/nav_sensor.h"
#include "sim/vehicle/trajectory.h"

namespace sonarloop::emulator {

// The state rendered and published with --pose-from: the trajectory's state at the same time
// with every part the external pose provides (its has_* flags) replaced by it, and its altitude.
vehicle::VehicleState merge_external_pose(vehicle::VehicleState state, const ExternalPose& pose);

struct PingProducerSetup {
  const render::PingRenderer* renderer = nullptr;
  const scene::Scene* scene = nullptr;
  const vehicle::Trajectory* trajectory = nullptr;
  const vehicle::NavSensorModel* nav = nullptr;
  const LocalTangentPlane* ltp = nullptr;
  const xtf::XtfFileHeader* header = nullptr;
  const Clock* clock = nullptr;  // times the renders
  std::uint64_t seed = 0;        // the scenario's seed (render randomness)
  SimTime ping_period_ns = 0;
  int threads = 1;                // workers (one scratch each)
  double prepare_ahead_m = 10.0;  // trajectory mode: prepare pings this far ahead along track
  // --pose-from (all three set, or none)
  const PoseSource* pose_source = nullptr;
  const Pacer* pacer = nullptr;
  SimTime stale_after_ns = 2 * kNanosecondsPerSecond;
  // each ping at the pose of (its due time - pose_delay_ns), emulator/pose_history.h
  SimTime pose_delay_ns = kNanosecondsPerSecond / 10;
};

class ScenePingProducer final : public PingProducer {
 public:
  explicit ScenePingProducer(const PingProducerSetup& setup);

  // UTC of t = 0; must be set before the first produce().
  void set_epoch_utc_ns(std::int64_t epoch_utc_ns) { epoch_utc_ns_ = epoch_utc_ns; }

  void produce(std::int64_t k, int worker, PingSlot& slot) override;
  // Trajectory mode: prepares ping k + prepare_ahead_pings().
  void work_ahead(std::int64_t k, int worker) override;
  // Stops waiting for ping times (end of the run).
  void cancel() override { cancelled_ = true; }

  bool external() const { return setup_.pose_source != nullptr; }
  // Trajectory mode: how many pings ahead a worker prepares.
  std::int64_t prepare_ahead_pings() const { return ahead_pings_; }
  // Start-up: prepares what pings first .. first + prepare_ahead_pings() read, with `threads`
  // threads, so that the workers start with their look-ahead already made (trajectory mode;
  // external mode: the trajectory's pose at that time, as a first guess).
  void prepare(std::int64_t first, int threads);

 private:
  // waits until the ping's wall time; false if cancelled
  bool wait_for_ping_time(SimTime t);

  PingProducerSetup setup_;
  vehicle::NavSensorModel exact_nav_;  // no errors: the external pose as navigation
  std::int64_t epoch_utc_ns_ = 0;
  std::int64_t ahead_pings_ = 1;
  std::vector<render::PingScratch> scratch_;  // one per worker (prepare() uses them too)
  std::atomic<bool> cancelled_{false};
};

}  // namespace sonarloop::emulator
