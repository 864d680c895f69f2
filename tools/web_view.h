#pragma once
// `--web HOST:PORT` of `run` and `onboard` (docs/web.md): the option, and the view (web/web_view.h)
// as one of the emulator's devices for `run --web`.
#include <memory>
#include <optional>

#include "drivers/net/host_port.h"
#include "emulator/device.h"
#include "emulator/run_stats.h"
#include "tools/args.h"
#include "web/web_view.h"

namespace sonarloop::tools {

// --web HOST:PORT or --web PORT (127.0.0.1); nullopt without it. UsageError for a bad value or
// a build without web support.
std::optional<net::HostPort> web_option(const Args& args);

// The run's statistics as the page shows them.
web::WebStats web_stats_of(const emulator::RunStats& s);

// `run --web`: the live view as one of the emulator's devices (emulator/device.h): every ping's
// datagram and the run's statistics to the hub, which never waits (a full browser queue drops,
// counted). `view` must outlive the emulator.
class WebViewDevice final : public emulator::Device {
 public:
  explicit WebViewDevice(web::WebView& view) : view_(view) {}
  void ping(const emulator::PingSlot& slot, std::span<const std::uint8_t> packet) override;
  void stats(const emulator::RunStats& s) override;
  bool on_wire() const override { return true; }
  std::vector<std::string> describe() const override { return {}; }  // its URL is printed

 private:
  web::WebView& view_;
};

}  // namespace sonarloop::tools
