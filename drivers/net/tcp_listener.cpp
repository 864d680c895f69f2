#include "drivers/net/tcp_listener.h"

#include <cerrno>

#include <fcntl.h>
#include <sys/socket.h>

namespace sonarloop::net {

bool set_nonblocking(int fd) {
  const int flags = ::fcntl(fd, F_GETFL, 0);
  return flags >= 0 && ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) == 0;
}

UniqueFd listen_tcp(const HostPort& address) {
  const SocketAddress addr = resolve(address);
  UniqueFd fd(::socket(addr.family(), SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
  if (!fd.valid()) return fd;
  const int one = 1;
  ::setsockopt(fd.get(), SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (::bind(fd.get(), addr.get(), addr.length) != 0 || ::listen(fd.get(), SOMAXCONN) != 0) {
    const int err = errno;
    fd.reset();
    errno = err;
  }
  return fd;
}

}  // namespace sonarloop::net
