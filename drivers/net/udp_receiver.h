#pragma once
// UDP datagram receiver bound to HOST:PORT (port 0 = an ephemeral port, see bound_port()).
//
// receive() waits up to a timeout and copies one datagram into the caller's buffer (no
// allocation). A datagram larger than the buffer is truncated and flagged. One thread receives
// at a time. The socket is bound without SO_REUSEADDR, so a port that is already taken gives a
// clear "address already in use" error instead of silently sharing the traffic.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "drivers/net/host_port.h"
#include "drivers/net/unique_fd.h"

namespace sonarloop::net {

struct ReceivedDatagram {
  std::size_t size = 0;           // bytes stored in the buffer
  bool truncated = false;         // the datagram was larger than the buffer; the rest is lost
  std::size_t datagram_size = 0;  // the datagram's real size
};

class UdpReceiver {
 public:
  // Binds `local`. receive_buffer_bytes > 0 asks for that SO_RCVBUF (capped by the kernel at
  // net.core.rmem_max; receive_buffer_bytes() reports what was granted). Throws
  // std::invalid_argument for a bad address, std::runtime_error naming the address otherwise.
  explicit UdpReceiver(const HostPort& local, int receive_buffer_bytes = 0);

  // Waits up to timeout_ms (0 = do not wait, < 0 = wait forever) for one datagram; nullopt on
  // timeout or when interrupted by a signal. Throws std::runtime_error on socket errors.
  std::optional<ReceivedDatagram> receive(std::span<std::uint8_t> buffer, int timeout_ms);

  std::uint16_t bound_port() const { return bound_.port; }
  const HostPort& bound_address() const { return bound_; }
  std::string describe() const;  // "udp on 127.0.0.1:5600"
  int receive_buffer_bytes() const;
  int fd() const { return fd_.get(); }

 private:
  HostPort bound_;
  UniqueFd fd_;
};

}  // namespace sonarloop::net
