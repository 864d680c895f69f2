#include "emulator/ping_producer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "common/parallel_for.h"
#include "drivers/xtf/xtf_codec.h"
#include "emulator/xtf_ping.h"

namespace sonarloop::emulator {
namespace {

// Longest single sleep while waiting for a ping time, so that cancel() is seen promptly.
constexpr std::int64_t kCancelPollNs = 20'000'000;
// Start-up prepares one ping per this much track of the look-ahead window.
constexpr double kStartupPrepareStride_m = 1.0;

}  // namespace

ScenePingProducer::ScenePingProducer(const PingProducerSetup& setup) : setup_(setup) {
  if (!setup_.renderer || !setup_.scene || !setup_.trajectory || !setup_.nav || !setup_.ltp ||
      !setup_.header || !setup_.clock || setup_.ping_period_ns <= 0) {
    throw std::invalid_argument("ScenePingProducer: incomplete setup");
  }
  if (setup_.external && !setup_.pacer) {
    throw std::invalid_argument("ScenePingProducer: an external pose source needs the pacer");
  }
  scratch_.resize(static_cast<std::size_t>(std::max(1, setup_.threads)));
  // pings in prepare_ahead_m of track at the trajectory's speed
  const double spacing_m =
      setup_.trajectory->desc().speed_m_s * static_cast<double>(setup_.ping_period_ns) * 1e-9;
  ahead_pings_ = std::max<std::int64_t>(
      1, static_cast<std::int64_t>(std::ceil(setup_.prepare_ahead_m / std::max(spacing_m, 1e-9))));
}

void ScenePingProducer::prepare(std::int64_t first, int threads) {
  if (external()) {
    const Pose p = setup_.trajectory->state_at(first * setup_.ping_period_ns).pose;
    setup_.renderer->prepare(*setup_.scene, p, {}, scratch_[0]);
    return;
  }
  // the look-ahead window, one ping per kStartupPrepareStride_m of track (the tiles are metres
  // wide), shared out over the threads
  const double spacing_m =
      setup_.trajectory->desc().speed_m_s * static_cast<double>(setup_.ping_period_ns) * 1e-9;
  const std::int64_t stride = std::max<std::int64_t>(
      1, static_cast<std::int64_t>(kStartupPrepareStride_m / std::max(spacing_m, 1e-9)));
  std::vector<std::int64_t> pings;
  for (std::int64_t k = first; k <= first + ahead_pings_; k += stride) {
    if (k * setup_.ping_period_ns >= setup_.trajectory->end_time()) break;
    pings.push_back(k);
  }
  pings.push_back(
      std::min(first + ahead_pings_, (setup_.trajectory->end_time() - 1) / setup_.ping_period_ns));
  const auto n = static_cast<int>(std::min<std::size_t>(
      pings.size(), static_cast<std::size_t>(std::max(1, std::min(threads, setup_.threads)))));
  parallel_for(pings.size(), n, [&](std::size_t i, int w) {
    const Pose p = setup_.trajectory->state_at(pings[i] * setup_.ping_period_ns).pose;
    setup_.renderer->prepare(*setup_.scene, p, {}, scratch_[static_cast<std::size_t>(w)]);
  });
}

void ScenePingProducer::work_ahead(std::int64_t k, int worker) {
  if (external()) return;  // poses are not known ahead
  const SimTime ahead = (k + ahead_pings_) * setup_.ping_period_ns;
  if (ahead >= setup_.trajectory->end_time()) return;
  setup_.renderer->prepare(*setup_.scene, setup_.trajectory->state_at(ahead).pose, {},
                           scratch_[static_cast<std::size_t>(worker)]);
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
  slot.abandoned = false;
  slot.produce_ns = 0;
  slot.packet_size = 0;
  PingTruth& truth = slot.truth;
  truth = PingTruth{};
  truth.t = t;
  truth.time_utc_ns = epoch_utc_ns_ + t;

  vehicle::VehicleState state;
  const vehicle::NavSensorModel* nav_model = setup_.nav;
  render::PingScratch& scratch = scratch_[static_cast<std::size_t>(worker)];
  if (external()) {
    if (!wait_for_ping_time(t)) {
      slot.emitted = false;
      return;
    }
    // the pose of the ping's own time (less the delay), not the latest sample as it is
    const ExternalPoseInput::Reading r = setup_.external->read(t);
    truth.external = true;
    truth.pose_age_ns = r.age_ns;
    truth.pose_extrapolated = r.extrapolated;
    if (!r.state) {
      slot.emitted = false;  // stale: no ping until a fresh pose arrives
      return;
    }
    state = *r.state;
    nav_model = &setup_.external->navigation();
  } else {
    state = setup_.trajectory->state_at(t);
  }

  // render and encode time
  const std::int64_t t0 = setup_.clock->now_ns();
  // the ping, from the true pose; given up (its window closed, or the run stops) it is cut
  // short and never sent
  render::RenderOptions options;
  options.abandon = slot.abandon;
  setup_.renderer->render(*setup_.scene, state.pose, setup_.seed, static_cast<std::uint64_t>(k),
                          options, scratch, slot.lines);
  if (render::abandoned(options)) {
    slot.abandoned = true;
    slot.produce_ns = setup_.clock->now_ns() - t0;
    return;
  }

  // the navigation the sonar records with it
  const vehicle::NavSolution nav = nav_model->measure(state);
  const PingNav pn = ping_nav_of(nav, *setup_.ltp, truth.time_utc_ns, slot.lines.altitude_m,
                                 static_cast<std::uint32_t>(k));
  make_xtf_ping(setup_.renderer->sonar(), *setup_.header, slot.lines, pn, slot.xtf);
  slot.packet_size = xtf::encode_ping(slot.xtf, *setup_.header, slot.packet);

  truth.pose = state.pose;
  truth.geo = setup_.ltp->to_geodetic(state.pose.position_W.x(), state.pose.position_W.y());
  truth.altitude_m = slot.lines.altitude_m;
  truth.speed_m_s = state.speed_m_s;
  slot.produce_ns = setup_.clock->now_ns() - t0;
}

}  // namespace sonarloop::emulator
