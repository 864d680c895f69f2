#include "drivers/can/can_transport.h"

#include <stdexcept>

#include "drivers/can/candump_log.h"
#include "drivers/can/socketcan.h"
#include "drivers/can/socketcand_server.h"
#include "drivers/net/host_port.h"

namespace sonarloop::can {
namespace {

constexpr std::size_t kMaxInterfaceChars = 15;  // IFNAMSIZ - 1

bool is_interface_name(const std::string& s) {
  if (s.empty() || s.size() > kMaxInterfaceChars) return false;
  for (char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-' || c == '.';
    if (!ok) return false;
  }
  return true;
}

}  // namespace

std::optional<CanFrame> CanTransport::receive(int /*timeout_ms*/) {
  throw std::logic_error(describe() + " cannot receive frames");
}

std::unique_ptr<CanTransport> open_can_transport(const std::string& spec,
                                                 const CanTransportOptions& options) {
  constexpr std::string_view kSocketcand = "socketcand:";
  constexpr std::string_view kLog = "log:";
  if (spec == "none") return std::make_unique<NullCanTransport>();
  if (spec.starts_with(kLog)) {
    const std::string path = spec.substr(kLog.size());
    if (path.empty())
      throw std::invalid_argument("--can " + spec + ": missing file name (log:FILE)");
    return std::make_unique<CandumpLogWriter>(path, options.channel);
  }
  if (spec.starts_with(kSocketcand)) {
    net::HostPort hp;
    try {
      hp = net::parse_host_port(spec.substr(kSocketcand.size()));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--can " + spec + ": " + e.what());
    }
    SocketcandServerOptions server_options;
    server_options.channel = options.channel;
    return std::make_unique<SocketcandServer>(hp, server_options);
  }
  if (is_interface_name(spec)) return std::make_unique<SocketCanTransport>(spec);
  throw std::invalid_argument("--can '" + spec +
                              "' is not a CAN transport: use a SocketCAN interface name (e.g. "
                              "vcan0), socketcand:HOST:PORT, log:FILE or none");
}

}  // namespace sonarloop::can
