#pragma once
// `run --classify`: the in-process onboard consumer (atr/in_process_onboard.h) as one of the
// emulator's devices (emulator/device.h), where the simulator meets the onboard side.
#include <exception>
#include <span>
#include <string>
#include <vector>

#include "atr/in_process_onboard.h"
#include "emulator/device.h"

namespace sonarloop::mission {

// `run --classify`: the in-process consumer as one of the emulator's devices
// (emulator/device.h): every ping's packet copied into its queue. `onboard` must outlive the
// emulator.
class OnboardDevice final : public emulator::Device {
 public:
  explicit OnboardDevice(atr::InProcessOnboard& onboard) : onboard_(onboard) {}
  void ping(const emulator::PingSlot&, std::span<const std::uint8_t> packet) override {
    onboard_.on_ping(packet);
  }
  bool on_wire() const override { return true; }
  std::vector<std::string> describe() const override { return {}; }  // said by run itself
  // The consumer's last decisions, while the devices added before it (the MCAP recording) are
  // still open (devices close in reverse order). An error is reported by run, which calls
  // finish() again.
  void close() override {
    try {
      onboard_.finish();
    } catch (const std::exception&) {
    }
  }

 private:
  atr::InProcessOnboard& onboard_;
};

}  // namespace sonarloop::mission
