#pragma once
// CAN transports (docs/style.md habit 6): one small interface for every way sonarloop puts CAN
// frames somewhere, and a factory for the `--can SPEC` option (docs/design.md, "Command line").
//
//   vcan0, can0, ...        SocketCAN raw socket on that interface (socketcan.h)
//   socketcand:HOST:PORT    a socketcand-compatible TCP server in rawmode (socketcand_server.h)
//   log:FILE                a candump log file (candump_log.h)
//   none                    frames are discarded
//
// Thread safety: send() may be called from several threads; receive() from one thread at a time,
// concurrently with send(). Implementations document anything stricter.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "drivers/can/can_frame.h"

namespace sonarloop::can {

// A frame with the time it was sent or received (ns; the epoch is the sender's: UNIX time for
// live and logged traffic).
struct TimedCanFrame {
  std::int64_t t_ns = 0;
  CanFrame frame;
};

class CanTransport {
 public:
  virtual ~CanTransport() = default;

  // Puts one frame on the transport. t_ns is the frame's timestamp (ns since the UNIX epoch for
  // live traffic), written by transports that carry time (log, socketcand); SocketCAN ignores
  // it. Never blocks for long: a transport that cannot keep up drops and counts.
  virtual void send(const CanFrame& frame, std::int64_t t_ns) = 0;

  // The next frame received within timeout_ms (0 = do not wait, < 0 = wait forever); nullopt on
  // timeout. Only where can_receive() is true; the default throws std::logic_error.
  virtual std::optional<CanFrame> receive(int timeout_ms);
  virtual bool can_receive() const { return false; }

  // One line for logs and error messages, e.g. "socketcand server on 127.0.0.1:29536 (vcan0)".
  virtual std::string describe() const = 0;

  // Pushes buffered frames out (file transports write their buffer to disk).
  virtual void flush() {}
};

// Discards every frame (`--can none`).
class NullCanTransport final : public CanTransport {
 public:
  void send(const CanFrame&, std::int64_t) override {}
  std::string describe() const override { return "none"; }
};

struct CanTransportOptions {
  std::string channel = "vcan0";  // bus name written to logs and announced by socketcand
};

// Opens the transport a `--can` SPEC names (see above). Throws std::invalid_argument for a
// malformed SPEC and std::runtime_error when the transport cannot be opened (the message names
// the SPEC and what to do instead, e.g. when the kernel has no CAN support).
std::unique_ptr<CanTransport> open_can_transport(const std::string& spec,
                                                 const CanTransportOptions& options = {});

}  // namespace sonarloop::can
