#include "atr/contact_writer.h"

#include <cerrno>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string_view>

namespace sonarloop::atr {
namespace {

// ContactWriter's destination prefix for UDP.
constexpr const char* kUdpPrefix = "udp:";

}  // namespace

ContactWriter::ContactWriter(const std::optional<std::string>& path, std::FILE* fallback) {
  if (path && path->rfind(kUdpPrefix, 0) == 0) {
    udp_ = std::make_unique<net::UdpSender>(
        net::parse_host_port(std::string_view(*path).substr(std::strlen(kUdpPrefix))));
    name_ = *path;
  } else if (path) {
    f_ = std::fopen(path->c_str(), "wb");
    if (!f_) {
      throw std::runtime_error("cannot create contacts file '" + *path +
                               "': " + std::strerror(errno));
    }
    owned_ = true;
    name_ = *path;
  } else {
    f_ = fallback;
    name_ = fallback == stdout ? "stdout" : "stderr";
  }
}

ContactWriter::~ContactWriter() {
  if (owned_ && f_) std::fclose(f_);
}

void ContactWriter::write(const Contact& c) {
  const std::string line = contact_json(c);
  if (udp_) {
    // a missing receiver is counted by the sender, never an error
    udp_->send(std::span(reinterpret_cast<const std::uint8_t*>(line.data()), line.size()));
    return;
  }
  if (std::fprintf(f_, "%s\n", line.c_str()) < 0 || std::fflush(f_) != 0) {
    throw std::runtime_error("cannot write to " + name_ + ": " + std::strerror(errno));
  }
}

std::string ContactWriter::describe() const {
  return name_;
}

}  // namespace sonarloop::atr
