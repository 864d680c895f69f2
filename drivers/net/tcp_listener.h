#pragma once
// The listening side of the TCP servers (the socketcand server, the live view's HTTP server):
// one way to open the socket, so both behave alike.
#include "drivers/net/host_port.h"
#include "drivers/net/unique_fd.h"

namespace sonarloop::net {

// A socket listening on `address` (port 0: a free port), non-blocking and close-on-exec, with
// SO_REUSEADDR so that a restarted server binds while old connections linger in TIME_WAIT, but
// not SO_REUSEPORT: a live listener on the port still makes the bind fail (EADDRINUSE) instead
// of sharing the port silently. The accept queue is the longest the kernel allows (SOMAXCONN):
// with a short one, clients connecting at once overflow it and wait for the kernel's SYN-ACK
// retries (1, 2, 4 s...). Throws std::invalid_argument for an address that is not numeric;
// returns an invalid fd with errno set when the socket cannot be opened, bound or listened on.
UniqueFd listen_tcp(const HostPort& address);

// O_NONBLOCK on `fd`; false with errno set on failure.
bool set_nonblocking(int fd);

}  // namespace sonarloop::net
