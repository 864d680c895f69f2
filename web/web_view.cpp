#include "web/web_view.h"

#include <time.h>

#include <cstdio>

namespace sonarloop::web {
namespace {

std::int64_t clock_ns(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

WebHubOptions hub_options(const std::optional<GeoPoint>& frame_origin) {
  WebHubOptions o;
  o.frame_origin = frame_origin;
  return o;
}

unsigned long long ull(std::uint64_t v) {
  return static_cast<unsigned long long>(v);
}

}  // namespace

WebView::WebView(const net::HostPort& address, const std::optional<GeoPoint>& frame_origin)
    : hub(hub_options(frame_origin)), server(hub, address) {}

std::unique_ptr<WebView> open_web_view(const std::optional<net::HostPort>& address,
                                       const std::optional<GeoPoint>& frame_origin,
                                       const char* who) {
  if (!address) return nullptr;
  auto view = std::make_unique<WebView>(*address, frame_origin);
  std::fprintf(stderr, "%s: web view on %s\n", who, view->server.url().c_str());
  return view;
}

WebStats web_stats_of(const atr::OnboardStats& s, double cpu_percent) {
  WebStats w;
  w.source = "onboard";
  w.pings = static_cast<std::int64_t>(s.receiver.pings);
  w.datagrams_lost = static_cast<std::int64_t>(s.receiver.lost);
  w.cpu_percent = cpu_percent;
  w.contacts = static_cast<std::int64_t>(s.contacts);
  return w;
}

void print_web_summary(const WebView& view) {
  const WebHubCounters c = view.hub.counters();
  const WebServerCounters s = view.server.counters();
  std::fprintf(stderr,
               "  web: %llu viewers (%llu refused), %llu lines, %llu events sent, %llu dropped "
               "(slow browsers), %llu pings not shown; %llu connections, %llu requests, %llu "
               "refused as malformed, %llu timed out, %llu replaced at the cap\n",
               ull(c.clients_total), ull(c.clients_refused), ull(c.lines), ull(c.events_sent),
               ull(c.events_dropped), ull(c.pings_not_shown), ull(s.connections), ull(s.requests),
               ull(s.bad_requests), ull(s.timeouts), ull(s.evicted));
}

CpuMeter::CpuMeter()
    : wall0_ns_(clock_ns(CLOCK_MONOTONIC)), cpu0_ns_(clock_ns(CLOCK_PROCESS_CPUTIME_ID)) {}

double CpuMeter::percent() const {
  const double wall = static_cast<double>(clock_ns(CLOCK_MONOTONIC) - wall0_ns_);
  const double cpu = static_cast<double>(clock_ns(CLOCK_PROCESS_CPUTIME_ID) - cpu0_ns_);
  return wall > 0 ? 100.0 * cpu / wall : 0.0;
}

}  // namespace sonarloop::web
