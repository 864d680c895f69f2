#include "tools/web_view.h"

#include <time.h>

#include <cstdio>
#include <string>

#include "tools/cli_helpers.h"

namespace sonarloop::tools {
namespace {

std::int64_t clock_ns(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace

namespace {

web::WebHubOptions hub_options(const std::optional<GeoPoint>& frame_origin) {
  web::WebHubOptions o;
  o.frame_origin = frame_origin;
  return o;
}

}  // namespace

WebView::WebView(const net::HostPort& address, const std::optional<GeoPoint>& frame_origin)
    : hub(hub_options(frame_origin)), server(hub, address) {}

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

std::unique_ptr<WebView> open_web_view(const std::optional<net::HostPort>& address,
                                       const std::optional<GeoPoint>& frame_origin,
                                       const char* who) {
  if (!address) return nullptr;
  auto view = std::make_unique<WebView>(*address, frame_origin);
  std::fprintf(stderr, "%s: web view on %s\n", who, view->server.url().c_str());
  return view;
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

web::WebStats web_stats_of(const atr::OnboardStats& s, double cpu_percent) {
  web::WebStats w;
  w.source = "onboard";
  w.pings = static_cast<std::int64_t>(s.receiver.pings);
  w.datagrams_lost = static_cast<std::int64_t>(s.receiver.lost);
  w.cpu_percent = cpu_percent;
  w.contacts = static_cast<std::int64_t>(s.contacts);
  return w;
}

void print_web_summary(const WebView& view) {
  const web::WebHubCounters c = view.hub.counters();
  std::fprintf(stderr,
               "  web: %llu viewers (%llu refused), %llu lines, %llu events sent, %llu dropped "
               "(slow browsers), %llu pings not shown\n",
               ull(c.clients_total), ull(c.clients_refused), ull(c.lines), ull(c.events_sent),
               ull(c.events_dropped), ull(c.pings_not_shown));
}

CpuMeter::CpuMeter()
    : wall0_ns_(clock_ns(CLOCK_MONOTONIC)), cpu0_ns_(clock_ns(CLOCK_PROCESS_CPUTIME_ID)) {}

double CpuMeter::percent() const {
  const double wall = static_cast<double>(clock_ns(CLOCK_MONOTONIC) - wall0_ns_);
  const double cpu = static_cast<double>(clock_ns(CLOCK_PROCESS_CPUTIME_ID) - cpu0_ns_);
  return wall > 0 ? 100.0 * cpu / wall : 0.0;
}

void WebViewDevice::ping(const emulator::PingSlot&, std::span<const std::uint8_t> packet) {
  view_.hub.push_datagram(packet);
}

void WebViewDevice::stats(const emulator::RunStats& s) {
  view_.hub.push_stats(web_stats_of(s));
}

}  // namespace sonarloop::tools
