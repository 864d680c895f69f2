#pragma once
// SocketCAN raw transport (docs/formats.md §4.1): socket(PF_CAN, SOCK_RAW, CAN_RAW) bound to one
// interface (vcan0, can0, ...), classic frames (struct can_frame, CAN_MTU 16 bytes), extended ids
// sent with CAN_EFF_FLAG.
//
// Where the kernel has no CAN support, socket() fails with EAFNOSUPPORT and the constructor
// throws a std::runtime_error that says so and names the fallbacks (socketcand:HOST:PORT,
// log:FILE). A missing interface is named in the error too.
//
// send() does not block: a full transmit queue drops the frame and counts it. receive() returns
// data frames only (remote, error and FD frames are skipped and counted). send() and receive()
// may run concurrently in two threads.
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>

#include "drivers/can/can_transport.h"
#include "drivers/net/unique_fd.h"

namespace sonarloop::can {

class SocketCanTransport final : public CanTransport {
 public:
  explicit SocketCanTransport(const std::string& interface_name);

  void send(const CanFrame& frame, std::int64_t t_ns) override;
  std::optional<CanFrame> receive(int timeout_ms) override;
  bool can_receive() const override { return true; }
  std::string describe() const override { return "socketcan " + interface_; }

  std::uint64_t frames_sent() const { return sent_.load(std::memory_order_relaxed); }
  std::uint64_t frames_dropped() const { return dropped_.load(std::memory_order_relaxed); }
  std::uint64_t frames_skipped() const { return skipped_.load(std::memory_order_relaxed); }

  // Whether socket(AF_CAN) works on this kernel; if not, `reason` gets the errno text.
  static bool kernel_supports_can(std::string* reason = nullptr);

 private:
  std::string interface_;
  net::UniqueFd fd_;
  std::atomic<std::uint64_t> sent_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::uint64_t> skipped_{0};
};

}  // namespace sonarloop::can
