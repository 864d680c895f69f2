#include "tools/web_option.h"

#include <stdexcept>
#include <string>

namespace sonarloop::tools {

std::optional<net::HostPort> web_option(const Args& args) {
  const auto text = args.get("--web");
  if (!text) return std::nullopt;
  // PORT alone: the loopback address
  const bool port_only = text->find_first_not_of("0123456789") == std::string::npos;
  try {
    return net::parse_host_port(port_only ? "127.0.0.1:" + *text : *text);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--web: ") + e.what());
  }
}

}  // namespace sonarloop::tools
