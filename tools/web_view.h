#pragma once
// `--web HOST:PORT` of `run` and `onboard` (docs/web.md): the live operator view's hub and
// server, the option, the statistics each command shows and the summary line at the end.
#include <cstdint>
#include <memory>
#include <optional>

#include "atr/onboard_pipeline.h"
#include "drivers/net/host_port.h"
#include "emulator/device.h"
#include "emulator/run_stats.h"
#include "tools/args.h"
#include "web/web_hub.h"
#include "web/web_server.h"

namespace sonarloop::tools {

// The statistics reach the page this often (wall seconds).
inline constexpr double kWebStatsEveryS = 1.0;

struct WebView {
  // Binds the server (throws std::runtime_error naming the address). `frame_origin`: that of
  // the contact reports (web::WebHubOptions).
  WebView(const net::HostPort& address, const std::optional<GeoPoint>& frame_origin);
  web::WebHub hub;
  web::WebServer server;
};

// --web HOST:PORT or --web PORT (127.0.0.1); nullopt without it. UsageError for a bad value or
// a build without web support.
std::optional<net::HostPort> web_option(const Args& args);

// Opens the view when asked for; prints its URL on stderr (even with --quiet: it is the way in).
std::unique_ptr<WebView> open_web_view(const std::optional<net::HostPort>& address,
                                       const std::optional<GeoPoint>& frame_origin,
                                       const char* who);

// The statistics as the page shows them: the run's, or the onboard consumer's.
web::WebStats web_stats_of(const emulator::RunStats& s);
web::WebStats web_stats_of(const atr::OnboardStats& s, double cpu_percent);

// "  web: 2 viewers, 1234 events sent, 0 dropped (slow browsers), 0 pings not shown".
void print_web_summary(const WebView& view);

// `run --web`: the live view as one of the emulator's devices (emulator/device.h): every ping's
// datagram and the run's statistics to the hub, which never waits (a full browser queue drops,
// counted). `view` must outlive the emulator.
class WebViewDevice final : public emulator::Device {
 public:
  explicit WebViewDevice(WebView& view) : view_(view) {}
  void ping(const emulator::PingSlot& slot, std::span<const std::uint8_t> packet) override;
  void stats(const emulator::RunStats& s) override;
  bool on_wire() const override { return true; }
  std::vector<std::string> describe() const override { return {}; }  // its URL is printed

 private:
  WebView& view_;
};

// CPU use of this process since construction, % of one core (for `onboard`).
class CpuMeter {
 public:
  CpuMeter();
  double percent() const;

 private:
  std::int64_t wall0_ns_, cpu0_ns_;
};

}  // namespace sonarloop::tools
