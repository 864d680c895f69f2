#include "drivers/net/udp_receiver.h"

#include <cerrno>
#include <stdexcept>

#include <poll.h>
#include <sys/socket.h>

#include "drivers/net/udp_sender.h"

namespace sonarloop::net {

UdpReceiver::UdpReceiver(const HostPort& local, int receive_buffer_bytes) : bound_(local) {
  const SocketAddress addr = resolve(local);
  fd_.reset(::socket(addr.family(), SOCK_DGRAM | SOCK_CLOEXEC, 0));
  if (!fd_.valid())
    throw std::runtime_error("UDP receiver on " + to_string(local) +
                             ": socket() failed: " + errno_text(errno));
  set_socket_buffer(fd_.get(), SO_RCVBUF, receive_buffer_bytes);
  if (::bind(fd_.get(), addr.get(), addr.length) != 0) {
    const int err = errno;
    std::string hint;
    if (err == EADDRINUSE) hint = " (another program is bound to this port; choose another port)";
    if (err == EADDRNOTAVAIL) hint = " (this address does not belong to this machine)";
    throw std::runtime_error("UDP receiver: cannot bind " + to_string(local) + ": " +
                             errno_text(err) + hint);
  }
  bound_.port = to_host_port(local_address(fd_.get())).port;
}

std::optional<ReceivedDatagram> UdpReceiver::receive(std::span<std::uint8_t> buffer,
                                                     int timeout_ms) {
  pollfd p{fd_.get(), POLLIN, 0};
  const int ready = ::poll(&p, 1, timeout_ms < 0 ? -1 : timeout_ms);
  if (ready < 0) {
    if (errno == EINTR) return std::nullopt;
    throw std::runtime_error(describe() + ": poll failed: " + errno_text(errno));
  }
  if (ready == 0) return std::nullopt;
  // MSG_TRUNC makes recv return the datagram's real length even when it did not fit
  const ssize_t n = ::recv(fd_.get(), buffer.data(), buffer.size(), MSG_TRUNC | MSG_DONTWAIT);
  if (n < 0) {
    const int err = errno;
    if (err == EINTR || err == EAGAIN || err == EWOULDBLOCK) return std::nullopt;
    throw std::runtime_error(describe() + ": recv failed: " + errno_text(err));
  }
  ReceivedDatagram d;
  d.datagram_size = static_cast<std::size_t>(n);
  d.truncated = d.datagram_size > buffer.size();
  d.size = d.truncated ? buffer.size() : d.datagram_size;
  return d;
}

std::string UdpReceiver::describe() const {
  return "udp on " + to_string(bound_);
}

int UdpReceiver::receive_buffer_bytes() const {
  return set_socket_buffer(fd_.get(), SO_RCVBUF, 0);
}

}  // namespace sonarloop::net
