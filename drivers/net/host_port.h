#pragma once
// HOST:PORT endpoints for the UDP and TCP transports.
//
// Accepted forms: "127.0.0.1:5600", "[::1]:5600" (IPv6 in brackets), "localhost:5600" (resolved
// to 127.0.0.1 without DNS). Only numeric addresses and "localhost" are accepted: sonarloop never
// performs name lookups. Port 0 asks the kernel for an ephemeral port when binding.
// Errors throw std::invalid_argument with the offending text and an example of what is allowed.
#include <cstdint>
#include <string>
#include <string_view>

#include <sys/socket.h>

namespace sonarloop::net {

struct HostPort {
  std::string host;  // numeric IPv4/IPv6 (without brackets) or "localhost"
  std::uint16_t port = 0;
  friend bool operator==(const HostPort&, const HostPort&) = default;
};

// Parses "HOST:PORT" (see above).
HostPort parse_host_port(std::string_view text);

// "127.0.0.1:5600" or "[::1]:5600".
std::string to_string(const HostPort& hp);

// A socket address ready for bind()/connect().
struct SocketAddress {
  sockaddr_storage storage{};
  socklen_t length = 0;
  int family() const { return storage.ss_family; }
  const sockaddr* get() const { return reinterpret_cast<const sockaddr*>(&storage); }
  sockaddr* get() { return reinterpret_cast<sockaddr*>(&storage); }
};

// Numeric address of a HostPort ("localhost" -> 127.0.0.1). Throws std::invalid_argument.
SocketAddress resolve(const HostPort& hp);

// The HostPort of a socket address (numeric host).
HostPort to_host_port(const SocketAddress& address);

// The local address a socket is bound to (getsockname). Throws std::runtime_error.
SocketAddress local_address(int fd);

}  // namespace sonarloop::net
