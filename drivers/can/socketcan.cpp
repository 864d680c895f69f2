#include "drivers/can/socketcan.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

namespace sonarloop::can {

bool SocketCanTransport::kernel_supports_can(std::string* reason) {
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    if (reason) *reason = net::errno_text(errno);
    return false;
  }
  ::close(fd);
  return true;
}

SocketCanTransport::SocketCanTransport(const std::string& interface_name)
    : interface_(interface_name) {
  if (interface_name.empty() || interface_name.size() >= IFNAMSIZ)
    throw std::invalid_argument("SocketCAN interface name '" + interface_name + "' must have 1.." +
                                std::to_string(IFNAMSIZ - 1) + " characters");
  fd_.reset(::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC | SOCK_NONBLOCK, CAN_RAW));
  if (!fd_.valid()) {
    const int err = errno;
    if (err == EAFNOSUPPORT)
      throw std::runtime_error(
          "SocketCAN is not available on this kernel (socket(AF_CAN): " + net::errno_text(err) +
          "); use --can socketcand:HOST:PORT or --can log:FILE");
    throw std::runtime_error("SocketCAN " + interface_name +
                             ": socket(AF_CAN) failed: " + net::errno_text(err));
  }
  const unsigned index = ::if_nametoindex(interface_name.c_str());
  if (index == 0) {
    const int err = errno;
    throw std::runtime_error("SocketCAN interface '" + interface_name + "' not found (" +
                             net::errno_text(err) +
                             "); create a virtual one with: ip link add dev " + interface_name +
                             " type vcan && ip link set up " + interface_name);
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(index);
  if (::bind(fd_.get(), reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
    throw std::runtime_error("SocketCAN " + interface_name +
                             ": bind failed: " + net::errno_text(errno));
}

void SocketCanTransport::send(const CanFrame& frame, std::int64_t /*t_ns*/) {
  can_frame raw{};
  raw.can_id =
      frame.extended ? ((frame.id & CAN_EFF_MASK) | CAN_EFF_FLAG) : (frame.id & CAN_SFF_MASK);
  raw.len = frame.len > CAN_MAX_DLEN ? CAN_MAX_DLEN : frame.len;
  std::memcpy(raw.data, frame.data.data(), raw.len);
  for (;;) {
    const ssize_t n = ::write(fd_.get(), &raw, sizeof raw);
    if (n == static_cast<ssize_t>(sizeof raw)) {
      sent_.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != ENOBUFS)
      throw std::runtime_error(describe() + ": write failed: " + net::errno_text(errno));
    dropped_.fetch_add(1, std::memory_order_relaxed);  // transmit queue full
    return;
  }
}

std::optional<CanFrame> SocketCanTransport::receive(int timeout_ms) {
  for (;;) {
    pollfd p{fd_.get(), POLLIN, 0};
    const int ready = ::poll(&p, 1, timeout_ms < 0 ? -1 : timeout_ms);
    if (ready < 0 && errno == EINTR) return std::nullopt;
    if (ready < 0)
      throw std::runtime_error(describe() + ": poll failed: " + net::errno_text(errno));
    if (ready == 0) return std::nullopt;
    can_frame raw{};
    const ssize_t n = ::read(fd_.get(), &raw, sizeof raw);
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) continue;
      throw std::runtime_error(describe() + ": read failed: " + net::errno_text(errno));
    }
    if (n != static_cast<ssize_t>(sizeof raw) || (raw.can_id & (CAN_RTR_FLAG | CAN_ERR_FLAG))) {
      skipped_.fetch_add(1, std::memory_order_relaxed);
      if (timeout_ms == 0) return std::nullopt;
      continue;  // a skipped frame restarts the wait: timeout_ms is a bound per frame read
    }
    CanFrame f;
    f.extended = (raw.can_id & CAN_EFF_FLAG) != 0;
    f.id = raw.can_id & (f.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
    f.len = raw.len > CAN_MAX_DLEN ? CAN_MAX_DLEN : raw.len;
    std::memcpy(f.data.data(), raw.data, f.len);
    return f;
  }
}

}  // namespace sonarloop::can
