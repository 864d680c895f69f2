// The run's statistics (run_stats.h): what the configuration fixes, filled once, and the counts
// and timings brought up to date for each report; and the one-line description of each output.
#include <cstdio>

#include "emulator/emulator_impl.h"

namespace sonarloop::emulator {

void Emulator::Impl::init_stats() {
  stats.rate = to_string(options.rate);
  stats.threads = options.threads;
  stats.ring_slots = options.ring_slots;
  stats.deadline_tolerance_ns = from_seconds(options.deadline_tolerance_s);
  stats.ping_period_s = seconds(period);
  stats.send_delay_s = seconds(send_delay);
  stats.bins_per_side = setup.bins;
  stats.bin_size_m = setup.desc.bin_size_m;
  stats.max_range_m = setup.desc.max_range_m;
  stats.packet_bytes = packet_bytes;
}

void Emulator::Impl::update_stats(std::int64_t now) {
  stats.sim_time_s = seconds(sim_reached);
  stats.wall_time_s = seconds(now - pacer.wall_start_ns());
  stats.cpu_time_s = seconds(clock.process_cpu_ns() - cpu_start_ns);
  stats.pings_due = stats.pings_sent + stats.pings_dropped + stats.pings_stale;
  stats.pings_rendered = queue->produced();
  stats.pings_abandoned = queue->abandoned();
  stats.render_mean_ms = stats.pings_rendered ? static_cast<double>(queue->produce_total_ns()) *
                                                    1e-6 / static_cast<double>(stats.pings_rendered)
                                              : 0.0;
  stats.render_max_ms = static_cast<double>(queue->produce_max_ns()) * 1e-6;
  stats.tiles_made = scene->seabed().tiles_made();
  stats.seabed_cache = scene->seabed().cache_stats();
  for (const auto& d : devices)
    d->add_stats(stats);
  if (pose_source) {
    const PoseSourceStats p = pose_source->stats();
    stats.has_pose_source = true;
    stats.pose_updates = p.updates;
    stats.pose_rejected = p.rejected;
    stats.pose_reanchors = p.reanchors;
    stats.pose_malformed = p.malformed;
    stats.pose_lost = p.lost;
    stats.pose_restarts = p.sequence_restarts;
  }
}

std::vector<std::string> Emulator::Impl::describe_outputs() const {
  std::vector<std::string> out;
  char buf[256];
  for (const auto& d : devices)
    for (std::string& line : d->describe())
      out.push_back(std::move(line));
  if (pose_source) {
    std::snprintf(buf, sizeof buf,
                  "pose from %s (pings at the pose of their time less %.3g s; "
                  "stale after %.3g s)",
                  pose_source->describe().c_str(), options.pose_delay_s, options.stale_after_s);
    out.emplace_back(buf);
  }
  return out;
}

}  // namespace sonarloop::emulator
