#pragma once
// UDP datagram sender: one connected socket to HOST:PORT (IPv4 or IPv6).
//
// Each send() is one datagram of at most kMaxUdpDatagramBytes (the IPv4 limit: 65535 - 20 IP
// header - 8 UDP header). The send path does not allocate. send() may be called from several
// threads at once (each call is one system call; counters are atomic).
//
// A missing receiver is not an error for a stream: a refused datagram (ICMP port unreachable,
// reported by Linux as ECONNREFUSED on a later send) and a full kernel queue (ENOBUFS, EAGAIN) are
// counted in dropped() and send() returns false. Other errors throw std::runtime_error.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "drivers/net/host_port.h"
#include "drivers/net/unique_fd.h"

namespace sonarloop::net {

inline constexpr std::size_t kMaxUdpDatagramBytes = 65507;

class UdpSender {
 public:
  // Connects to `destination`. send_buffer_bytes > 0 asks for that SO_SNDBUF (the kernel caps it
  // at net.core.wmem_max; send_buffer_bytes() reports what was granted). Throws
  // std::invalid_argument for a bad address, std::runtime_error for socket errors.
  explicit UdpSender(const HostPort& destination, int send_buffer_bytes = 0);

  // Sends one datagram. Throws std::invalid_argument if it is larger than kMaxUdpDatagramBytes.
  // Returns false if the datagram was dropped (see above).
  bool send(std::span<const std::uint8_t> datagram);

  const HostPort& destination() const { return destination_; }
  std::string describe() const;   // "udp to 127.0.0.1:5600"
  int send_buffer_bytes() const;  // SO_SNDBUF as granted by the kernel
  std::uint64_t datagrams_sent() const { return sent_.load(std::memory_order_relaxed); }
  std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }
  int fd() const { return fd_.get(); }

 private:
  HostPort destination_;
  UniqueFd fd_;
  std::atomic<std::uint64_t> sent_{0};
  std::atomic<std::uint64_t> dropped_{0};
};

// Sets SO_SNDBUF or SO_RCVBUF (if bytes > 0) and returns the size the kernel reports.
int set_socket_buffer(int fd, int option, int bytes);

}  // namespace sonarloop::net
