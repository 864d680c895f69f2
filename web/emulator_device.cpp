#include "web/emulator_device.h"

namespace sonarloop::web {

WebStats web_stats_of(const emulator::RunStats& s) {
  WebStats w;
  w.source = "run";
  w.sim_time_s = s.sim_time_s;
  w.pings = static_cast<std::int64_t>(s.pings_sent);
  w.deadline_misses = static_cast<std::int64_t>(s.deadline_misses());
  if (s.ping_lateness.count()) w.lateness_p99_ms = s.ping_lateness.quantile_ns(0.99) * 1e-6;
  w.datagrams_lost = static_cast<std::int64_t>(s.udp_dropped);
  w.cpu_percent = s.cpu_percent();
  return w;
}

void WebViewDevice::ping(const emulator::PingSlot&, std::span<const std::uint8_t> packet) {
  hub_.push_datagram(packet);
}

void WebViewDevice::stats(const emulator::RunStats& s) {
  hub_.push_stats(web_stats_of(s));
}

}  // namespace sonarloop::web
