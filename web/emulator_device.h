#pragma once
// `run --web`: the live view as one of the emulator's devices (emulator/device.h). Every ping's
// datagram and the run's statistics go to the hub, which never waits (a full browser queue
// drops, counted). The view's server is web_view.h's; this device only feeds its hub.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "emulator/device.h"
#include "emulator/run_stats.h"
#include "web/web_hub.h"

namespace sonarloop::web {

// The emulator's statistics as the page shows them (source "run").
WebStats web_stats_of(const emulator::RunStats& s);

class WebViewDevice final : public emulator::Device {
 public:
  // `hub` must outlive the emulator.
  explicit WebViewDevice(WebHub& hub) : hub_(hub) {}
  void ping(const emulator::PingSlot& slot, std::span<const std::uint8_t> packet) override;
  void stats(const emulator::RunStats& s) override;
  bool on_wire() const override { return true; }
  std::vector<std::string> describe() const override { return {}; }  // its URL is printed

 private:
  WebHub& hub_;
};

}  // namespace sonarloop::web
