#include "emulator/nav_can_device.h"

#include <utility>

namespace sonarloop::emulator {

NavCanDevice::NavCanDevice(std::unique_ptr<can::CanTransport> transport)
    : transport_(std::move(transport)) {}

void NavCanDevice::nav(std::span<const can::CanFrame> frames, std::int64_t utc_ns) {
  for (const can::CanFrame& f : frames)
    transport_->send(f, utc_ns);
}

std::vector<std::string> NavCanDevice::describe() const {
  return {"can: " + transport_->describe() + " (NMEA 2000 navigation)"};
}

void NavCanDevice::close() {
  transport_->flush();
}

}  // namespace sonarloop::emulator
