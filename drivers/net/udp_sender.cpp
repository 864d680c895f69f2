#include "drivers/net/udp_sender.h"

#include <cerrno>
#include <stdexcept>

#include <sys/socket.h>

namespace sonarloop::net {

int set_socket_buffer(int fd, int option, int bytes) {
  if (bytes > 0) {
    // failure is not fatal: the kernel default stays in force and is reported below
    ::setsockopt(fd, SOL_SOCKET, option, &bytes, sizeof bytes);
  }
  int actual = 0;
  socklen_t len = sizeof actual;
  if (::getsockopt(fd, SOL_SOCKET, option, &actual, &len) != 0) return 0;
  return actual;
}

UdpSender::UdpSender(const HostPort& destination, int send_buffer_bytes)
    : destination_(destination) {
  const SocketAddress addr = resolve(destination);
  fd_.reset(::socket(addr.family(), SOCK_DGRAM | SOCK_CLOEXEC, 0));
  if (!fd_.valid())
    throw std::runtime_error("UDP sender to " + to_string(destination) +
                             ": socket() failed: " + errno_text(errno));
  set_socket_buffer(fd_.get(), SO_SNDBUF, send_buffer_bytes);
  if (::connect(fd_.get(), addr.get(), addr.length) != 0)
    throw std::runtime_error("UDP sender to " + to_string(destination) +
                             ": connect() failed: " + errno_text(errno));
}

bool UdpSender::send(std::span<const std::uint8_t> datagram) {
  if (datagram.size() > kMaxUdpDatagramBytes)
    throw std::invalid_argument("UDP datagram of " + std::to_string(datagram.size()) +
                                " bytes to " + to_string(destination_) + " exceeds the " +
                                std::to_string(kMaxUdpDatagramBytes) + "-byte maximum");
  for (;;) {
    const ssize_t n = ::send(fd_.get(), datagram.data(), datagram.size(), MSG_NOSIGNAL);
    if (n >= 0) {
      sent_.fetch_add(1, std::memory_order_relaxed);
      return true;
    }
    const int err = errno;
    if (err == EINTR) continue;
    if (err == ECONNREFUSED || err == ENOBUFS || err == EAGAIN || err == EWOULDBLOCK) {
      dropped_.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    throw std::runtime_error("UDP send of " + std::to_string(datagram.size()) + " bytes to " +
                             to_string(destination_) + " failed: " + errno_text(err));
  }
}

std::string UdpSender::describe() const {
  return "udp to " + to_string(destination_);
}

int UdpSender::send_buffer_bytes() const {
  return set_socket_buffer(fd_.get(), SO_SNDBUF, 0);
}

}  // namespace sonarloop::net
