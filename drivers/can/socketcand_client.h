#pragma once
// A socketcand client in rawmode (docs/formats.md §4.4): connects to a socketcand server
// (sonarloop's SocketcandServer or the real socketcand daemon), performs "< hi >" /
// "< open CHANNEL >" / "< rawmode >", then yields the frames the server pushes and sends frames
// with "< send ID DLC B0 .. >". Used for hardware-in-the-loop input and to test the server.
//
// The byte stream is cut into "< ... >" elements, so it does not matter how the server's writes
// are split or coalesced. "< error ... >" elements are counted and skipped.
//
// Threads: send() and receive() may run concurrently (one receiving thread).
#include <atomic>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

#include "drivers/can/can_transport.h"
#include "drivers/can/socketcand_protocol.h"
#include "drivers/net/host_port.h"
#include "drivers/net/unique_fd.h"

namespace sonarloop::can {

struct SocketcandClientOptions {
  std::string channel = "vcan0";
  int timeout_ms = 5000;  // for connecting and for each handshake reply
};

class SocketcandClient final : public CanTransport {
 public:
  // Connects and enters rawmode. Throws std::runtime_error naming the server and the step that
  // failed (connect, "< hi >", open, rawmode).
  explicit SocketcandClient(const net::HostPort& server, SocketcandClientOptions options = {});

  // Sends "< send ... >" (t_ns is not part of the protocol). Throws std::runtime_error if the
  // connection is lost.
  void send(const CanFrame& frame, std::int64_t t_ns) override;
  std::optional<CanFrame> receive(int timeout_ms) override;
  // Like receive(), with the server's timestamp of the frame.
  std::optional<TimedCanFrame> receive_timed(int timeout_ms);
  bool can_receive() const override { return true; }
  std::string describe() const override;

  // False once the server has closed the connection (receive() then throws).
  bool connected() const { return connected_.load(); }
  std::uint64_t errors_received() const { return errors_.load(); }

 private:
  // Reads what is available (waiting up to timeout_ms for the first bytes) into the parser.
  // Returns false on timeout. Throws when the connection is closed or broken.
  bool read_some(int timeout_ms);
  // The next element within timeout_ms, or nullopt.
  std::optional<std::string> next_element(int timeout_ms);
  void expect(const char* what, const char* step);

  net::HostPort server_;
  SocketcandClientOptions options_;
  net::UniqueFd fd_;
  std::mutex send_mu_;
  SocketcandStreamParser parser_;  // receiving thread only
  std::atomic<bool> connected_{false};
  std::atomic<std::uint64_t> errors_{0};
};

}  // namespace sonarloop::can
