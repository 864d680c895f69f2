// `sonarloop run`'s console report (run_report.h).
#include "emulator/run_report.h"

#include <cstdio>
#include <limits>

namespace sonarloop::emulator {
namespace {

double ms_of(double ns) {
  return ns * 1e-6;
}

}  // namespace

void print_run_summary(const emulator::RunStats& s, const char* how) {
  std::fprintf(stderr, "sonarloop run: %s after %.2f s of simulation in %.2f s (rate %s)\n", how,
               s.sim_time_s, s.wall_time_s, s.rate.c_str());
  if (s.realtime != "normal") std::fprintf(stderr, "  publisher: %s\n", s.realtime.c_str());
  std::fprintf(stderr,
               "  pings: %llu sent, %llu deadline misses (%llu late > %g ms, %llu of them not "
               "rendered in time; %llu dropped)",
               static_cast<unsigned long long>(s.pings_sent),
               static_cast<unsigned long long>(s.deadline_misses()),
               static_cast<unsigned long long>(s.pings_late),
               ms_of(static_cast<double>(s.deadline_tolerance_ns)),
               static_cast<unsigned long long>(s.pings_late_render),
               static_cast<unsigned long long>(s.pings_dropped));
  if (s.pings_stale || s.stale_episodes) {
    std::fprintf(stderr, ", %llu not emitted (stale pose, %llu episodes)",
                 static_cast<unsigned long long>(s.pings_stale),
                 static_cast<unsigned long long>(s.stale_episodes));
  }
  std::fprintf(stderr, "\n");
  if (s.ping_lateness.count()) {
    std::fprintf(stderr,
                 "  lateness (send deadline -> datagram sent): p50 %.3f ms, p99 %.3f ms, max %.3f "
                 "ms\n",
                 ms_of(s.ping_lateness.quantile_ns(0.5)), ms_of(s.ping_lateness.quantile_ns(0.99)),
                 ms_of(static_cast<double>(s.ping_lateness.max_ns())));
    std::fprintf(stderr,
                 "  latency (ping time -> datagram sent, incl. the %.1f ms receive window): p50 "
                 "%.3f ms, p99 %.3f ms, max %.3f ms\n",
                 s.send_delay_s * 1e3, ms_of(s.ping_latency.quantile_ns(0.5)),
                 ms_of(s.ping_latency.quantile_ns(0.99)),
                 ms_of(static_cast<double>(s.ping_latency.max_ns())));
  }
  if (s.has_pose_source) {
    std::fprintf(stderr,
                 "  pose: %llu updates, %llu rejected as implausible (%llu re-anchored), %llu "
                 "malformed, %llu lost, %llu sender restarts\n",
                 static_cast<unsigned long long>(s.pose_updates),
                 static_cast<unsigned long long>(s.pose_rejected),
                 static_cast<unsigned long long>(s.pose_reanchors),
                 static_cast<unsigned long long>(s.pose_malformed),
                 static_cast<unsigned long long>(s.pose_lost),
                 static_cast<unsigned long long>(s.pose_restarts));
  }
  if (s.wall_time_s > 0) {
    std::fprintf(stderr, "  throughput: %.1f pings/s (%.2fx real time)\n",
                 static_cast<double>(s.pings_sent) / s.wall_time_s, s.sim_time_s / s.wall_time_s);
  }
  std::fprintf(stderr, "  nav: %llu frames in %llu samples, %llu skipped, %llu withheld",
               static_cast<unsigned long long>(s.nav_frames),
               static_cast<unsigned long long>(s.nav_samples),
               static_cast<unsigned long long>(s.nav_frames_skipped),
               static_cast<unsigned long long>(s.nav_frames_withheld));
  if (s.nav_lateness.count()) {
    std::fprintf(stderr, "; lateness p50 %.3f ms, p99 %.3f ms, max %.3f ms",
                 ms_of(s.nav_lateness.quantile_ns(0.5)), ms_of(s.nav_lateness.quantile_ns(0.99)),
                 ms_of(static_cast<double>(s.nav_lateness.max_ns())));
  }
  std::fprintf(stderr, "\n");
  if (s.udp_datagrams) {
    std::fprintf(stderr,
                 "  udp: %llu datagrams (%llu file headers), %llu refused or dropped by the "
                 "kernel (e.g. nothing listening on the port)\n",
                 static_cast<unsigned long long>(s.udp_datagrams),
                 static_cast<unsigned long long>(s.udp_header_datagrams),
                 static_cast<unsigned long long>(s.udp_dropped));
  }
  if (s.mcap_messages) {
    std::fprintf(stderr, "  mcap: %llu messages\n",
                 static_cast<unsigned long long>(s.mcap_messages));
  }
  if (s.imc_datagrams) {
    std::fprintf(stderr, "  imc: %llu packets, %llu refused or dropped by the kernel\n",
                 static_cast<unsigned long long>(s.imc_datagrams),
                 static_cast<unsigned long long>(s.imc_dropped));
  }
  std::string abandoned;
  if (s.pings_abandoned) {
    abandoned = ", " + std::to_string(s.pings_abandoned) + " more cut short when given up";
  }
  std::fprintf(stderr,
               "  render: %llu pings, %.2f ms mean, %.2f ms max on %d threads%s; %llu heightmap "
               "tiles made\n",
               static_cast<unsigned long long>(s.pings_rendered), s.render_mean_ms, s.render_max_ms,
               s.threads, abandoned.c_str(), static_cast<unsigned long long>(s.tiles_made));
  const seabed::SeabedCacheStats& c = s.seabed_cache;
  const auto percent = [](const seabed::TileCacheCounters& k) {
    const std::uint64_t asked = k.hits + k.misses;
    return asked ? 100.0 * static_cast<double>(k.hits) / static_cast<double>(asked) : 100.0;
  };
  std::fprintf(stderr,
               "  seabed caches: heightmap %.1f %% hits, noise %.1f %% hits; %.0f of %.0f MB "
               "held; %llu tiles evicted\n",
               percent(c.heightmap), percent(c.noise), static_cast<double>(c.bytes) / 1048576.0,
               static_cast<double>(c.budget_bytes) / 1048576.0,
               static_cast<unsigned long long>(c.heightmap.evictions + c.noise.evictions));
  std::fprintf(stderr, "  cpu: %.1f %% of one core (%.2f s); start-up %.2f s\n", s.cpu_percent(),
               s.cpu_time_s, s.startup_s);
}

void print_run_setup(const emulator::Emulator& emu, const emulator::EmulatorOptions& o) {
  const auto& s = emu.sonar();
  std::fprintf(stderr,
               "sonar '%s': %d samples per side x %.3g m (%.4g m range), ping every %.2f ms "
               "(%.2f pings/s), %zu-byte XTF pings sent %.1f ms after the ping time\n",
               s.desc.name.c_str(), s.bins, s.desc.bin_size_m, s.desc.max_range_m,
               static_cast<double>(emu.ping_period_ns()) * 1e-6,
               1e9 / static_cast<double>(emu.ping_period_ns()), emu.packet_bytes(),
               static_cast<double>(emu.send_delay_ns()) * 1e-6);
  if (emu.end_time() == std::numeric_limits<SimTime>::max()) {
    std::fprintf(stderr, "duration: until stopped (Ctrl-C)\n");
  } else {
    std::fprintf(stderr, "duration: %.2f s of simulation at rate %s\n",
                 static_cast<double>(emu.end_time()) * 1e-9, emulator::to_string(o.rate).c_str());
  }
  for (const auto& line : emu.describe_outputs())
    std::fprintf(stderr, "%s\n", line.c_str());
  if (!o.udp) {
    std::fprintf(stderr,
                 "hint: no --udp given, pings are not streamed (e.g. --udp 127.0.0.1:5600)\n");
  }
}

}  // namespace sonarloop::emulator
