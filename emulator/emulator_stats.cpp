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
  stats.render_mean_ms = stats.pings_rendered ? static_cast<double>(queue->produce_total_ns()) *
                                                    1e-6 / static_cast<double>(stats.pings_rendered)
                                              : 0.0;
  stats.render_max_ms = static_cast<double>(queue->produce_max_ns()) * 1e-6;
  stats.tiles_made = scene->seabed().tiles_made();
  if (udp) {
    stats.udp_dropped = udp->dropped();
  }
  if (recording) stats.recorded_pings = recording->pings();
  if (pose_source) {
    const PoseSourceStats p = pose_source->stats();
    stats.has_pose_source = true;
    stats.pose_updates = p.updates;
    stats.pose_rejected = p.rejected;
    stats.pose_reanchors = p.reanchors;
    stats.pose_malformed = p.malformed;
    stats.pose_lost = p.lost;
  }
}

std::vector<std::string> Emulator::Impl::describe_outputs() const {
  std::vector<std::string> out;
  char buf[256];
  if (udp) {
    std::snprintf(buf, sizeof buf,
                  "%s: one XTF ping per datagram (%zu bytes), file header (%zu bytes) first and "
                  "every %.0f s",
                  udp->describe().c_str(), packet_bytes, header_bytes.size(), kHeaderRepeatS);
    out.emplace_back(buf);
  }
  for (const auto& c : cans)
    out.push_back("can: " + c->describe() + " (NMEA 2000 navigation)");
  if (recording) {
    out.push_back("record: " + recording->dir() + "/{pings.xtf, nav.log, truth.csv}");
  }
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
