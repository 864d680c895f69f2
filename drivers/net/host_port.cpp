#include "drivers/net/host_port.h"

#include <charconv>
#include <cstring>
#include <stdexcept>

#include <arpa/inet.h>
#include <netinet/in.h>

#include "drivers/net/unique_fd.h"

namespace sonarloop::net {
namespace {

[[noreturn]] void fail(std::string_view text, const std::string& what) {
  throw std::invalid_argument("invalid address '" + std::string(text) + "': " + what +
                              " (expected HOST:PORT, e.g. 127.0.0.1:5600, [::1]:5600 or "
                              "localhost:5600)");
}

}  // namespace

HostPort parse_host_port(std::string_view text) {
  std::string_view host;
  std::string_view port;
  if (!text.empty() && text.front() == '[') {
    const auto close = text.find(']');
    if (close == std::string_view::npos) fail(text, "missing ']' after the IPv6 address");
    host = text.substr(1, close - 1);
    if (close + 1 >= text.size() || text[close + 1] != ':') fail(text, "missing ':PORT'");
    port = text.substr(close + 2);
  } else {
    const auto colon = text.rfind(':');
    if (colon == std::string_view::npos) fail(text, "missing ':PORT'");
    host = text.substr(0, colon);
    port = text.substr(colon + 1);
    if (host.find(':') != std::string_view::npos)
      fail(text, "an IPv6 address must be written in brackets, e.g. [::1]:5600");
  }
  if (host.empty()) fail(text, "missing host");
  if (port.empty()) fail(text, "missing port");
  unsigned value = 0;
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (ec != std::errc() || end != port.data() + port.size())
    fail(text, "port '" + std::string(port) + "' is not a number");
  if (value > 65535) fail(text, "port " + std::string(port) + " is out of range 0..65535");
  HostPort hp{std::string(host), static_cast<std::uint16_t>(value)};
  resolve(hp);  // validates the host
  return hp;
}

std::string to_string(const HostPort& hp) {
  const bool v6 = hp.host.find(':') != std::string::npos;
  return (v6 ? "[" + hp.host + "]" : hp.host) + ":" + std::to_string(hp.port);
}

SocketAddress resolve(const HostPort& hp) {
  SocketAddress out;
  const std::string host = hp.host == "localhost" ? "127.0.0.1" : hp.host;
  sockaddr_in v4{};
  sockaddr_in6 v6{};
  if (::inet_pton(AF_INET, host.c_str(), &v4.sin_addr) == 1) {
    v4.sin_family = AF_INET;
    v4.sin_port = htons(hp.port);
    std::memcpy(&out.storage, &v4, sizeof v4);
    out.length = sizeof v4;
  } else if (::inet_pton(AF_INET6, host.c_str(), &v6.sin6_addr) == 1) {
    v6.sin6_family = AF_INET6;
    v6.sin6_port = htons(hp.port);
    std::memcpy(&out.storage, &v6, sizeof v6);
    out.length = sizeof v6;
  } else {
    throw std::invalid_argument("invalid host '" + hp.host +
                                "': expected a numeric IPv4 or IPv6 address or 'localhost' "
                                "(no name lookups)");
  }
  return out;
}

HostPort to_host_port(const SocketAddress& address) {
  char buf[INET6_ADDRSTRLEN] = {};
  HostPort hp;
  if (address.family() == AF_INET) {
    sockaddr_in v4{};
    std::memcpy(&v4, &address.storage, sizeof v4);
    ::inet_ntop(AF_INET, &v4.sin_addr, buf, sizeof buf);
    hp.port = ntohs(v4.sin_port);
  } else if (address.family() == AF_INET6) {
    sockaddr_in6 v6{};
    std::memcpy(&v6, &address.storage, sizeof v6);
    ::inet_ntop(AF_INET6, &v6.sin6_addr, buf, sizeof buf);
    hp.port = ntohs(v6.sin6_port);
  }
  hp.host = buf;
  return hp;
}

SocketAddress local_address(int fd) {
  SocketAddress out;
  out.length = sizeof out.storage;
  if (::getsockname(fd, out.get(), &out.length) != 0)
    throw std::runtime_error("getsockname failed: " + errno_text(errno));
  return out;
}

}  // namespace sonarloop::net
