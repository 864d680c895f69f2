#include "emulator/sonar_udp_device.h"

#include <cstdio>
#include <utility>

namespace sonarloop::emulator {

SonarUdpDevice::SonarUdpDevice(const net::HostPort& destination, int send_buffer_bytes,
                               std::vector<std::uint8_t> header_bytes, std::size_t packet_bytes)
    : udp_(destination, send_buffer_bytes),
      header_bytes_(std::move(header_bytes)),
      packet_bytes_(packet_bytes) {}

void SonarUdpDevice::send(std::span<const std::uint8_t> datagram) {
  udp_.send(datagram);
  ++datagrams_;
  bytes_ += datagram.size();
}

void SonarUdpDevice::ping(const PingSlot& slot, std::span<const std::uint8_t> packet) {
  if (!header_sent_ || slot.truth.t >= next_header_t_) {
    send(header_bytes_);
    header_sent_ = true;
    next_header_t_ = slot.truth.t + from_seconds(kHeaderRepeatS);
    ++header_datagrams_;
  }
  send(packet);
}

void SonarUdpDevice::add_stats(RunStats& stats) const {
  stats.udp_datagrams = datagrams_;
  stats.udp_header_datagrams = header_datagrams_;
  stats.udp_bytes = bytes_;
  stats.udp_dropped = udp_.dropped();
}

std::vector<std::string> SonarUdpDevice::describe() const {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "%s: one XTF ping per datagram (%zu bytes), file header (%zu bytes) first and "
                "every %.0f s",
                udp_.describe().c_str(), packet_bytes_, header_bytes_.size(), kHeaderRepeatS);
  return {buf};
}

}  // namespace sonarloop::emulator
