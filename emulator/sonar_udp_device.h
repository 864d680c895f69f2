#pragma once
// The sonar's stream (--udp HOST:PORT; emulator.h, "UDP stream"): each ping's XTF packet as one
// datagram, preceded by the file header's datagram first and then before the first ping at or
// after every kHeaderRepeatS of simulation time since the last one, so that a receiver that
// starts late learns the channel layout within 2 s.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "drivers/net/host_port.h"
#include "drivers/net/udp_sender.h"
#include "emulator/device.h"
#include "sim/core/sim_time.h"

namespace sonarloop::emulator {

// The file header datagram is repeated every this many seconds of simulation time.
inline constexpr double kHeaderRepeatS = 2.0;

class SonarUdpDevice final : public Device {
 public:
  // header_bytes: the encoded XTF file header; packet_bytes: every ping's size (for describe).
  SonarUdpDevice(const net::HostPort& destination, int send_buffer_bytes,
                 std::vector<std::uint8_t> header_bytes, std::size_t packet_bytes);

  void ping(const PingSlot& slot, std::span<const std::uint8_t> packet) override;
  bool on_wire() const override { return true; }
  // udp_datagrams, udp_header_datagrams, udp_bytes, udp_dropped
  void add_stats(RunStats& stats) const override;
  std::vector<std::string> describe() const override;

 private:
  void send(std::span<const std::uint8_t> datagram);

  net::UdpSender udp_;
  std::vector<std::uint8_t> header_bytes_;
  std::size_t packet_bytes_;
  bool header_sent_ = false;
  SimTime next_header_t_ = 0;
  std::uint64_t datagrams_ = 0, header_datagrams_ = 0, bytes_ = 0;
};

}  // namespace sonarloop::emulator
