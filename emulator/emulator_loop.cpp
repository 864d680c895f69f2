// The publisher's loop (emulator_impl.h; the threads and the schedules are described in
// emulator.h): pings and navigation samples merged in simulation time, paced with absolute
// deadlines (pacer.h) or sent as fast as rendering allows (--rate max); each event sent to UDP
// and CAN, handed to the in-process consumers and recorded: to the devices, device.h.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

#include "emulator/emulator_impl.h"

namespace sonarloop::emulator {

void Emulator::Impl::loop() {
  NavSchedule navs;
  std::int64_t k = 0;
  const std::int64_t interval_ns =
      options.stats_interval_s > 0 ? from_seconds(options.stats_interval_s) : kNever;
  std::int64_t next_stats = interval_ns == kNever ? kNever : pacer.wall_start_ns() + interval_ns;

  for (;;) {
    if (stop_requested()) break;
    if (queue->failed()) throw std::runtime_error(queue->error());
    Turn turn;
    turn.ping_left = k < n_pings;
    turn.nav_t = navs.next_time();
    turn.nav_left = turn.nav_t < end;
    if (!turn.ping_left && !turn.nav_left) break;
    // read the wake-up generation before looking at the queue, so no notification is lost
    turn.generation = queue->wakeup().generation();
    turn.now = clock.now_ns();
    if (turn.now >= next_stats) {
      update_stats(turn.now);
      if (hooks.on_stats) hooks.on_stats(stats);
      for (auto& d : devices)
        d->stats(stats);
      next_stats =
          interval_ns == kNever ? kNever : next_deadline(next_stats, interval_ns, turn.now);
    }
    turn.next_stats = next_stats;
    if (pacer.paced()) {
      turn_paced(navs, k, turn);
    } else {
      turn_max_rate(navs, k, turn);
    }
  }
}

// --rate max: as fast as possible, strictly in time order (navigation first at equal times);
// waits only for the next ping to be rendered.
void Emulator::Impl::turn_max_rate(NavSchedule& navs, std::int64_t& k, const Turn& turn) {
  if (turn.nav_left && (!turn.ping_left || turn.nav_t <= send_time(k))) {
    publish_nav(navs.pop(turn.nav_t));
    return;
  }
  if (const PingSlot* slot = queue->ready(k)) {
    publish_ping(*slot, k);
    queue->release(k);
    ++k;
    return;
  }
  queue->wakeup().wait_until(std::min(turn.now + kStopPollNs, turn.next_stats), turn.generation);
}

// Paced: every event at its deadline. A ping is sent in its window (ping_window) as soon as it is
// rendered and dropped when the window closes; otherwise sleeps until the next deadline.
void Emulator::Impl::turn_paced(NavSchedule& navs, std::int64_t& k, const Turn& turn) {
  const std::int64_t now = turn.now;
  if (turn.nav_left && now >= pacer.wall_of(turn.nav_t)) {
    publish_nav(navs.pop(pacer.sim_of(now)));
    return;
  }
  std::int64_t wake = std::min(now + kStopPollNs, turn.next_stats);
  if (turn.nav_left) wake = std::min(wake, pacer.wall_of(turn.nav_t));
  bool waiting_for_render = false;
  if (turn.ping_left) {
    const std::int64_t open = pacer.wall_of(send_time(k));
    const std::int64_t close = pacer.wall_of(send_time(k + 1));
    switch (ping_window(open, close, now)) {
      case PingWindow::kMissed:
        drop_ping(k);
        ++k;
        return;
      case PingWindow::kOpen:
        if (const PingSlot* slot = queue->ready(k)) {
          publish_ping(*slot, k);
          queue->release(k);
          ++k;
          return;
        }
        waiting_for_render = true;  // late: sent as soon as it is rendered, until `close`
        unrendered_at_open = k;
        wake = std::min(wake, close);
        break;
      case PingWindow::kEarly:
        wake = std::min(wake, open);
        break;
    }
  }
  if (waiting_for_render) {
    queue->wakeup().wait_until(wake, turn.generation);
  } else {
    clock.sleep_until(wake);
  }
}

// ---- navigation ----

// The navigation solution at sample time t: the navigation sensor model's, or with --pose-from
// the external pose's, exactly. Without a fresh external pose, only the PGNs that do not depend on
// it stay in `due` (counted as withheld) and the solution is empty.
vehicle::NavSolution Emulator::Impl::measure_nav(SimTime t, NavPgnMask& due) {
  if (!external_pose) return nav->measure(trajectory->state_at(t));
  // as the pings: the pose of the sample's own time less the delay (external_pose.h)
  const ExternalPoseInput::Reading r = external_pose->read(t);
  if (!r.state) {
    // no pose to publish: only what does not depend on it
    const NavPgnMask kept = due & pose_free_pgns();
    stats.nav_frames_withheld += static_cast<std::uint64_t>(std::popcount(due & ~kept));
    due = kept;
    vehicle::NavSolution none;
    none.t = t;
    return none;
  }
  vehicle::VehicleState state = *r.state;
  // an external pose without altitude: the altimeter's (the DVL's) reading of the scene, the
  // height above the seabed's large-scale relief (as the vehicle's depth planning sees it)
  if (!std::isfinite(state.altitude_m)) {
    const Vec3& p = state.pose.position_W;
    state.altitude_m =
        scenario.scene.water.depth_m - scene->seabed().base_elevation(p.x(), p.y()) - p.z();
  }
  return external_pose->navigation().measure(state);
}

void Emulator::Impl::publish_nav(const NavSchedule::Sample& sample) {
  const SimTime t = sample.t;
  stats.nav_frames_skipped += static_cast<std::uint64_t>(sample.skipped);
  NavPgnMask due = sample.due;
  const vehicle::NavSolution solution = measure_nav(t, due);
  const std::int64_t utc = epoch_utc_ns + t;
  const std::size_t n = make_nav_frames(solution, ltp, utc, sid.current(), due, frames);
  const std::span<const can::CanFrame> sample_frames(frames.data(), n);
  if (due & kPositionPgnBit) {
    for (auto& d : devices)
      d->nav_solution(solution, utc);
  }
  for (auto& d : devices)
    d->nav(sample_frames, utc);
  sid.advance();
  ++stats.nav_samples;
  stats.nav_frames += n;
  sim_reached = std::max(sim_reached, t);
  if (pacer.paced()) stats.nav_lateness.add(clock.now_ns() - pacer.wall_of(t));
}

// ---- pings ----

// A ping that was not emitted (no fresh external pose): counted, and said once per stale episode.
void Emulator::Impl::note_stale_ping(const PingSlot& slot, std::int64_t k) {
  ++stats.pings_stale;
  if (!pings_stale) {
    pings_stale = true;
    ++stats.stale_episodes;
    char msg[256];
    if (slot.truth.pose_age_ns < 0) {
      std::snprintf(msg, sizeof msg,
                    "warning: no pose received yet from %s: no pings until one arrives",
                    pose_source ? pose_source->describe().c_str() : "the pose source");
    } else {
      std::snprintf(msg, sizeof msg,
                    "warning: the external pose is stale (last update %.2f s ago, limit %.2f s):"
                    " pings paused at ping %lld until a fresh pose arrives",
                    seconds(slot.truth.pose_age_ns), options.stale_after_s,
                    static_cast<long long>(k));
    }
    message(msg);
  }
}

void Emulator::Impl::publish_ping(const PingSlot& slot, std::int64_t k) {
  sim_reached = std::max(sim_reached, slot.truth.t);
  if (!slot.emitted) {
    note_stale_ping(slot, k);
    return;
  }
  if (pings_stale) {
    pings_stale = false;
    char msg[128];
    std::snprintf(msg, sizeof msg, "external pose fresh again: pings resumed at ping %lld",
                  static_cast<long long>(k));
    message(msg);
  }
  const std::span<const std::uint8_t> packet(slot.packet.data(), slot.packet_size);
  // the devices on the wire (the in-process consumers among them); lateness is measured once
  // they have it
  for (auto& d : devices)
    if (d->on_wire()) d->ping(slot, packet);
  if (slot.truth.pose_extrapolated) ++stats.pings_extrapolated;
  if (pacer.paced()) {
    const std::int64_t sent = clock.now_ns();
    const std::int64_t lateness = sent - pacer.wall_of(slot.truth.t + send_delay);
    stats.ping_lateness.add(lateness);
    stats.ping_latency.add(sent - pacer.wall_of(slot.truth.t));
    if (lateness > stats.deadline_tolerance_ns) {
      ++stats.pings_late;
      if (unrendered_at_open == k) ++stats.pings_late_render;
    }
  }
  for (auto& d : devices)
    if (!d->on_wire()) d->ping(slot, packet);
  ++stats.pings_sent;
}

void Emulator::Impl::drop_ping(std::int64_t k) {
  ++stats.pings_dropped;
  sim_reached = std::max(sim_reached, k * period);
  queue->release(k);
}

}  // namespace sonarloop::emulator
