#include "emulator/device.h"

namespace sonarloop::emulator {

Device::~Device() = default;
void Device::ping(const PingSlot&, std::span<const std::uint8_t>) {}
void Device::nav(std::span<const can::CanFrame>, std::int64_t) {}
void Device::nav_solution(const vehicle::NavSolution&, std::int64_t) {}
void Device::add_stats(RunStats&) const {}
void Device::stats(const RunStats&) {}
void Device::close() {}

}  // namespace sonarloop::emulator
