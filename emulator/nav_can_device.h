#pragma once
// The navigation bus (--can SPEC, one device per transport): each navigation sample's NMEA 2000
// frames (nav_frames.h) sent on one CAN transport (SocketCAN, a socketcand server, a candump
// log; drivers/can/can_transport.h).
#include <memory>

#include "drivers/can/can_transport.h"
#include "emulator/device.h"

namespace sonarloop::emulator {

class NavCanDevice final : public Device {
 public:
  explicit NavCanDevice(std::unique_ptr<can::CanTransport> transport);

  void nav(std::span<const can::CanFrame> frames, std::int64_t utc_ns) override;
  bool on_wire() const override { return true; }
  std::vector<std::string> describe() const override;
  void close() override;  // flushes the transport

 private:
  std::unique_ptr<can::CanTransport> transport_;
};

}  // namespace sonarloop::emulator
