#pragma once
// Contact reports out of the onboard consumer (`onboard`, `run --classify`): one JSON line per
// contact (atr/contact.h) to a file, a stream or UDP.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "atr/contact.h"
#include "drivers/net/udp_sender.h"

namespace sonarloop::atr {

// Contact reports, one JSON line each, flushed line by line (a reader sees them live). To a file
// (created or truncated), to an already open stream (stdout, stderr), or with a path
// "udp:HOST:PORT" as UDP datagrams there, one contact's JSON line (no newline) per datagram
// (atr/contact.h; what `sonarloop autonomy --contacts` reads).
class ContactWriter {
 public:
  // Throws std::runtime_error naming the file if it cannot be created, std::invalid_argument
  // for a malformed udp:HOST:PORT.
  explicit ContactWriter(const std::optional<std::string>& path, std::FILE* fallback);
  ~ContactWriter();
  ContactWriter(const ContactWriter&) = delete;
  ContactWriter& operator=(const ContactWriter&) = delete;

  void write(const Contact& c);
  std::string describe() const;  // the file name, "stdout" / "stderr", or "udp:HOST:PORT"

 private:
  std::unique_ptr<net::UdpSender> udp_;
  std::FILE* f_ = nullptr;
  bool owned_ = false;
  std::string name_;
};

}  // namespace sonarloop::atr
