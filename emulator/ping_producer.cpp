#include "emulator/ping_producer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "drivers/xtf/xtf_codec.h"
#include "emulator/xtf_ping.h"

namespace sonarloop::emulator {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
// Longest single sleep while waiting for a ping time, so that cancel() is seen promptly.
constexpr std::int64_t kCancelPollNs = 20'000'000;

}  // namespace

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

ScenePingProducer::ScenePingProducer(const PingProducerSetup& setup)
    : setup_(setup), exact_nav_(vehicle::NavNoiseDesc{}, setup.seed) {
  if (!setup_.renderer || !setup_.trajectory || !setup_.nav || !setup_.ltp || !setup_.header ||
      !setup_.views || !setup_.clock || setup_.ping_period_ns <= 0) {
    throw std::invalid_argument("ScenePingProducer: incomplete setup");
  }
  if (setup_.pose_source && !setup_.pacer) {
    throw std::invalid_argument("ScenePingProducer: an external pose source needs the pacer");
  }
  scratch_.resize(static_cast<std::size_t>(std::max(1, setup_.threads)));
  // pings per chunk: chunk_length_m of track at the trajectory's speed
  const double spacing_m =
      setup_.trajectory->desc().speed_m_s * static_cast<double>(setup_.ping_period_ns) * 1e-9;
  chunk_pings_ = std::max<std::int64_t>(
      1, static_cast<std::int64_t>(std::ceil(setup_.chunk_length_m / std::max(spacing_m, 1e-9))));
  plan_.reserve(64);
}

scene::Box2 ScenePingProducer::chunk_region(std::int64_t c) {
  while (static_cast<std::int64_t>(plan_.size()) <= c) {
    const auto ci = static_cast<std::int64_t>(plan_.size());
    // the swaths of the chunk's pings
    scene::Box2 swath;
    for (std::int64_t i = 0; i < chunk_pings_; ++i) {
      const SimTime t = (ci * chunk_pings_ + i) * setup_.ping_period_ns;
      const scene::Box2 r = setup_.renderer->swath_region(setup_.trajectory->state_at(t).pose);
      swath = i == 0 ? r : box_union(swath, r);
    }
    swath = setup_.views->clip(swath);
    if (!plan_.empty() && box_contains(plan_.back(), swath)) {
      plan_.push_back(plan_.back());  // the previous chunk's view already covers it
    } else {
      plan_.push_back(swath);
    }
  }
  return plan_[static_cast<std::size_t>(c)];
}

scene::Box2 ScenePingProducer::view_region_for_ping(std::int64_t k) {
  std::lock_guard<std::mutex> lock(plan_mu_);
  return chunk_region(k / chunk_pings_);
}

void ScenePingProducer::prepare(std::int64_t first, int threads) {
  if (external()) {
    const Pose p = setup_.trajectory->state_at(first * setup_.ping_period_ns).pose;
    const scene::Box2 swath = setup_.renderer->swath_region(p);
    setup_.views->build_now(box_expand(swath, setup_.chunk_length_m), threads);
    return;
  }
  setup_.views->build_now(view_region_for_ping(first), threads);
  // and the next chunk's, in the background
  setup_.views->prefetch(view_region_for_ping((first / chunk_pings_ + 1) * chunk_pings_));
}

bool ScenePingProducer::wait_for_ping_time(SimTime t) {
  const Clock& clock = *setup_.clock;
  const std::int64_t due = setup_.pacer->wall_of(t);
  for (;;) {
    if (cancelled_) return false;
    const std::int64_t now = clock.now_ns();
    if (now >= due) return true;
    // Clock::sleep_until is not const (a simulated clock advances); the pacer's clock is the
    // same object as setup_.clock
    setup_.pacer->clock().sleep_until(std::min(due, now + kCancelPollNs));
  }
}

void ScenePingProducer::produce(std::int64_t k, int worker, PingSlot& slot) {
  const SimTime t = k * setup_.ping_period_ns;
  slot.index = k;
  slot.emitted = true;
  slot.produce_ns = 0;
  slot.packet_size = 0;
  PingTruth& truth = slot.truth;
  truth = PingTruth{};
  truth.t = t;
  truth.time_utc_ns = epoch_utc_ns_ + t;

  vehicle::VehicleState state;
  std::shared_ptr<const scene::SceneView> view;
  const vehicle::NavSensorModel* nav_model = setup_.nav;
  if (external()) {
    if (!wait_for_ping_time(t)) {
      slot.emitted = false;
      return;
    }
    const std::int64_t now = setup_.clock->now_ns();
    const std::optional<ExternalPose> ext = setup_.pose_source->latest();
    truth.external = true;
    truth.pose_age_ns = ext ? now - ext->received_ns : -1;
    if (!ext || truth.pose_age_ns > setup_.stale_after_ns) {
      slot.emitted = false;  // stale: no ping until a fresh pose arrives
      return;
    }
    // what the source lacks comes from the trajectory
    state = merge_external_pose(setup_.trajectory->state_at(t), *ext);
    nav_model = &exact_nav_;
    const scene::Box2 swath = setup_.renderer->swath_region(state.pose);
    view = setup_.views->get_covering(swath, box_expand(swath, setup_.chunk_length_m));
    setup_.views->prefetch_covering(box_expand(swath, 0.5 * setup_.chunk_length_m),
                                    box_expand(swath, setup_.chunk_length_m));
  } else {
    state = setup_.trajectory->state_at(t);
    const std::int64_t c = k / chunk_pings_;
    const scene::Box2 region = view_region_for_ping(k);
    const scene::Box2 next = view_region_for_ping((c + 1) * chunk_pings_);
    if (next.min != region.min || next.max != region.max) setup_.views->prefetch(next);
    view = setup_.views->get(region);
  }
  if (!view) {
    // the view cache stopped (cancelled run, or a failed build)
    const std::string why = setup_.views->error();
    if (!why.empty()) throw std::runtime_error(why);
    slot.emitted = false;
    return;
  }

  // render and encode time (view waits are counted by the view cache)
  const std::int64_t t0 = setup_.clock->now_ns();
  // the ping, from the true pose
  setup_.renderer->render(*view, state.pose, setup_.seed, static_cast<std::uint64_t>(k), {},
                          scratch_[static_cast<std::size_t>(worker)], slot.lines);

  // the navigation the sonar records with it
  const vehicle::NavSolution nav = nav_model->measure(state);
  PingNav pn;
  pn.time_utc_ns = truth.time_utc_ns;
  pn.sensor = setup_.ltp->to_geodetic(nav.north_m, nav.east_m);
  pn.heading_deg = nav.heading * kDegPerRad;
  pn.pitch_deg = nav.pitch * kDegPerRad;
  pn.roll_deg = nav.roll * kDegPerRad;
  pn.depth_m = nav.depth_m;
  pn.altitude_m = std::isfinite(nav.altitude_m) ? nav.altitude_m : slot.lines.altitude_m;
  pn.speed_m_s = nav.speed_over_ground_m_s;
  pn.ping_number = static_cast<std::uint32_t>(k);
  make_xtf_ping(setup_.renderer->sonar(), *setup_.header, slot.lines, pn, slot.xtf);
  slot.packet_size = xtf::encode_ping(slot.xtf, *setup_.header, slot.packet);

  truth.pose = state.pose;
  truth.geo = setup_.ltp->to_geodetic(state.pose.position_W.x(), state.pose.position_W.y());
  truth.altitude_m = slot.lines.altitude_m;
  truth.speed_m_s = state.speed_m_s;
  slot.produce_ns = setup_.clock->now_ns() - t0;
}

}  // namespace sonarloop::emulator
