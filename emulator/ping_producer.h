#pragma once
// What a render worker does for ping k (RenderQueue's PingProducer): the pose at the ping time,
// the scene view, the render, the navigation the sonar records, and the XTF packet.
//
// Ping time t_k = k·ping_period (ns since the mission start), UTC = epoch + t_k. Two pose modes:
//
// Trajectory (default). The true pose is Trajectory::state_at(t_k); the XTF ping's navigation
// fields come from NavSensorModel::measure(state) (what the vehicle's navigation reports, with
// the scenario's errors), the render from the true pose, with randomness keyed by (seed, k).
// The ping is therefore a pure function of (scenario, k): workers may render it any time ahead,
// on any thread. Views follow a fixed plan: the pings are cut into chunks of chunk_pings()
// consecutive pings (chunk_length_m of track); chunk c's view covers the swaths (max range
// around the sonar) of all its pings, clipped to the seabed, or is chunk c-1's view when that
// already covers them. The plan depends only on the trajectory, so the same ping is always
// rendered with the same view (byte-identical pings). Rendering chunk c prefetches chunk c+1's
// view on the view cache's thread.
//
// External pose (--pose-from). The worker waits for the ping's wall time, takes the source's
// latest pose and renders from it. Fields the source does not provide (its has_* flags) come
// from the trajectory at t_k: position (north, east), depth, heading, pitch and roll; velocity
// and yaw rate always do (no external source sends them). A pose older than stale_after (or none
// yet) gives no ping (slot.emitted = false). The navigation recorded in the XTF ping is that
// pose without added errors (it is the vehicle's own navigation). Views: any cached view that
// covers the swath, else one built around it with chunk_length_m of margin; a view covering a
// margin of half that is prefetched as the vehicle nears the edge.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

#include "drivers/xtf/xtf_types.h"
#include "emulator/pacer.h"
#include "emulator/pose_source.h"
#include "emulator/render_queue.h"
#include "emulator/view_cache.h"
#include "sim/core/geodesy.h"
#include "sim/render/ping_renderer.h"
#include "sim/vehicle/nav_sensor.h"
#include "sim/vehicle/trajectory.h"

namespace sonarloop::emulator {

// The state rendered and published with --pose-from: the trajectory's state at the same time
// with every part the external pose provides (its has_* flags) replaced by it, and its altitude.
vehicle::VehicleState merge_external_pose(vehicle::VehicleState state, const ExternalPose& pose);

struct PingProducerSetup {
  const render::PingRenderer* renderer = nullptr;
  const vehicle::Trajectory* trajectory = nullptr;
  const vehicle::NavSensorModel* nav = nullptr;
  const LocalTangentPlane* ltp = nullptr;
  const xtf::XtfFileHeader* header = nullptr;
  ViewCache* views = nullptr;
  const Clock* clock = nullptr;  // times the renders
  std::uint64_t seed = 0;        // the scenario's seed (render randomness)
  SimTime ping_period_ns = 0;
  int threads = 1;                // workers (one scratch each)
  double chunk_length_m = 100.0;  // along-track length of a view chunk / HIL view margin
  // --pose-from (all three set, or none)
  const PoseSource* pose_source = nullptr;
  const Pacer* pacer = nullptr;
  SimTime stale_after_ns = 2 * kNanosecondsPerSecond;
};

class ScenePingProducer final : public PingProducer {
 public:
  explicit ScenePingProducer(const PingProducerSetup& setup);

  // UTC of t = 0; must be set before the first produce().
  void set_epoch_utc_ns(std::int64_t epoch_utc_ns) { epoch_utc_ns_ = epoch_utc_ns; }

  void produce(std::int64_t k, int worker, PingSlot& slot) override;
  // Stops waiting for ping times and for views (the view cache is cancelled: end of the run).
  void cancel() override {
    cancelled_ = true;
    setup_.views->cancel();
  }

  bool external() const { return setup_.pose_source != nullptr; }
  // Trajectory mode: pings per view chunk, and the (clipped) region of ping k's view.
  std::int64_t chunk_pings() const { return chunk_pings_; }
  scene::Box2 view_region_for_ping(std::int64_t k);
  // Start-up: builds the view that ping `first` needs on the calling thread (trajectory mode;
  // external mode: around the trajectory's pose at t = 0, as a first guess).
  void prepare(std::int64_t first, int threads);

 private:
  scene::Box2 chunk_region(std::int64_t c);  // plan_mu_ held
  // waits until the ping's wall time; false if cancelled
  bool wait_for_ping_time(SimTime t);

  PingProducerSetup setup_;
  vehicle::NavSensorModel exact_nav_;  // no errors: the external pose as navigation
  std::int64_t epoch_utc_ns_ = 0;
  std::int64_t chunk_pings_ = 1;
  std::vector<render::PingScratch> scratch_;  // one per worker
  std::mutex plan_mu_;
  std::vector<scene::Box2> plan_;  // view region of chunk c (grows one chunk at a time)
  std::atomic<bool> cancelled_{false};
};

}  // namespace sonarloop::emulator
