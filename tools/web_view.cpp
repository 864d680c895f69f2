#include "tools/web_view.h"

#include <string>

namespace sonarloop::tools {

std::optional<net::HostPort> web_option(const Args& args) {
  const auto text = args.get("--web");
  if (!text) return std::nullopt;
  if (!web::web_available())
    throw UsageError(std::string("--web: ") + web::WebUnavailable().what());
  // PORT alone: the loopback address
  const bool port_only = text->find_first_not_of("0123456789") == std::string::npos;
  try {
    return net::parse_host_port(port_only ? "127.0.0.1:" + *text : *text);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--web: ") + e.what());
  }
}

web::WebStats web_stats_of(const emulator::RunStats& s) {
  web::WebStats w;
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
  view_.hub.push_datagram(packet);
}

void WebViewDevice::stats(const emulator::RunStats& s) {
  view_.hub.push_stats(web_stats_of(s));
}

}  // namespace sonarloop::tools
