#pragma once
// The live operator view as `run --web` and `onboard --web` open it (docs/web.md): the hub and
// its server on one address, the statistics `onboard` shows, the summary line at the end.
#include <cstdint>
#include <memory>
#include <optional>

#include "atr/onboard_pipeline.h"
#include "common/geodesy.h"
#include "drivers/net/host_port.h"
#include "web/web_hub.h"
#include "web/web_server.h"

namespace sonarloop::web {

// The statistics reach the page this often (wall seconds).
inline constexpr double kWebStatsEveryS = 1.0;

struct WebView {
  // Binds the server (throws std::runtime_error naming the address). `frame_origin`: that of
  // the contact reports (WebHubOptions).
  WebView(const net::HostPort& address, const std::optional<GeoPoint>& frame_origin);
  WebHub hub;
  WebServer server;
};

// Opens the view when asked for; prints its URL on stderr (even with --quiet: it is the way in).
std::unique_ptr<WebView> open_web_view(const std::optional<net::HostPort>& address,
                                       const std::optional<GeoPoint>& frame_origin,
                                       const char* who);

// The onboard consumer's statistics as the page shows them.
WebStats web_stats_of(const atr::OnboardStats& s, double cpu_percent);

// "  web: 2 viewers (0 refused), 669 lines, 634 events sent, 0 dropped (slow browsers), 0 pings
// not shown; 5 connections, 7 requests, 0 refused as malformed, 0 timed out, 0 replaced at the
// cap".
void print_web_summary(const WebView& view);

// CPU use of this process since construction, % of one core (for `onboard`).
class CpuMeter {
 public:
  CpuMeter();
  double percent() const;

 private:
  std::int64_t wall0_ns_, cpu0_ns_;
};

}  // namespace sonarloop::web
