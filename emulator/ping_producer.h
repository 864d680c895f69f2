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
// External pose (--pose-from). The worker waits for the ping's wall time and renders from the
// external pose of the ping's time (ExternalPoseInput, external_pose.h: the sequence the
// navigation frames follow too): what the source does not send comes from the trajectory at t_k,
// a pose older than stale_after (or none yet) gives no ping (slot.emitted = false), and the
// navigation recorded in the XTF ping is that pose without added errors (it is the vehicle's own
// navigation). Poses are not known ahead: what a ping reads is made when it is rendered.
#include <atomic>
#include <cstdint>
#include <vector>

#include "common/geodesy.h"
#include "drivers/xtf/xtf_types.h"
#include "emulator/external_pose.h"
#include "emulator/pacer.h"
#include "emulator/render_queue.h"
#include "sim/render/ping_renderer.h"
#include "sim/vehicle/nav_sensor.h"
#include "sim/vehicle/trajectory.h"

namespace sonarloop::emulator {

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
  // --pose-from (both set, or none): each ping at the external pose of its time
  // (external_pose.h), rendered once the pacer's wall clock reaches it
  const ExternalPoseInput* external = nullptr;
  const Pacer* pacer = nullptr;
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

  bool external() const { return setup_.external != nullptr; }
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
  std::int64_t epoch_utc_ns_ = 0;
  std::int64_t ahead_pings_ = 1;
  std::vector<render::PingScratch> scratch_;  // one per worker (prepare() uses them too)
  std::atomic<bool> cancelled_{false};
};

}  // namespace sonarloop::emulator
