#pragma once
// A socketcand-compatible TCP server in rawmode (docs/formats.md §4.4): python-can's
// `can.Bus(interface="socketcand", host=..., port=..., channel="vcan0")`, socketcand clients
// and SocketcandClient read the frames sonarloop sends, and can send frames back.
//
// Per client: "< hi >" on connect (alone), "< open CHANNEL >" -> "< ok >", "< rawmode >" ->
// "< ok >", then, after rawmode_start_delay_ms (so the client's recv() of "< ok >" is not
// coalesced with frames), one "\n< frame ID SEC.USEC DATA >" per send() (the newline before the
// frame, not after it: socketcand_protocol.h says why). Any channel name is accepted: there is
// one bus. "< send ID DLC B0 .. >" from a client (in rawmode, or in the BCM
// mode that follows "open") is queued for receive(). "< echo >" is answered with "< echo >".
//
// Threads: the server runs one I/O thread (accept, read commands, flush backlogs). send() writes
// to each streaming client directly with a non-blocking send(), one system call per frame and
// client, and never blocks: what the kernel does not take goes to a per-client backlog of
// client_backlog_bytes; a client whose backlog overflows is disconnected and counted (a slow
// reader never stalls the emulator). send(), receive() and the accessors are thread-safe.
// The destructor (or stop()) closes every connection and joins the thread.
//
// Handshake: a client that has not sent "< open CHANNEL >" within handshake_timeout_ms is closed
// and counted, and when all max_clients slots are taken a new connection evicts the oldest
// client still waiting for its "< open >" (idle or half-open connections never lock real clients
// out); the new connection is refused only when every client has opened the bus.
//
// Errors: a port already in use (or any bind/listen failure) throws std::runtime_error naming
// the address.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "drivers/can/can_transport.h"
#include "drivers/net/host_port.h"
#include "drivers/net/unique_fd.h"

namespace sonarloop::can {

inline constexpr std::uint16_t kSocketcandDefaultPort = 29536;

struct SocketcandServerOptions {
  std::string channel = "vcan0";                  // bus name, used in describe()
  std::size_t client_backlog_bytes = 256 * 1024;  // per client, beyond the kernel socket buffer
  std::size_t max_clients = 16;                   // further connections get an error and close
  int handshake_timeout_ms =
      5000;  // a client must send "< open CHANNEL >" within this; <= 0: no limit
  std::size_t receive_queue_frames = 4096;  // frames from clients; oldest dropped beyond
  int rawmode_start_delay_ms = 100;         // pause between rawmode's "< ok >" and frames
  // Called (outside internal locks, from the I/O thread or a send() caller) for each counted
  // problem such as a dropped slow client. Default: a "warning: ..." line on stderr.
  std::function<void(const std::string&)> on_warning;
};

struct SocketcandServerStats {
  std::uint64_t frames_sent = 0;      // send() calls
  std::uint64_t frames_received = 0;  // frames from clients queued for receive()
  std::uint64_t clients_accepted = 0;
  std::uint64_t clients_rejected = 0;           // over max_clients, all of them past "< open >"
  std::uint64_t clients_dropped_handshake = 0;  // no "< open >" in time, or evicted for a newer
  std::uint64_t clients_dropped_slow = 0;       // backlog overflow
  // frames that clients dropped as slow never received whole: handed to the client and never
  // begun on its socket (its backlog, the frame that overflowed it), or begun and cut off
  std::uint64_t frames_dropped_slow = 0;
  std::uint64_t clients_disconnected = 0;     // closed by the peer or a socket error
  std::uint64_t protocol_errors = 0;          // malformed or unsupported commands
  std::uint64_t receive_queue_overflows = 0;  // frames dropped because receive() lagged
};

class SocketcandServer final : public CanTransport {
 public:
  // Listens on `listen_address` (port 0: an ephemeral port, see bound_port()) and starts the
  // I/O thread.
  explicit SocketcandServer(const net::HostPort& listen_address,
                            SocketcandServerOptions options = {});
  ~SocketcandServer() override;
  SocketcandServer(const SocketcandServer&) = delete;
  SocketcandServer& operator=(const SocketcandServer&) = delete;

  // Sends the frame to every client in rawmode. t_ns: the frame's timestamp (ns since the UNIX
  // epoch). Allocation-free unless a client has to be dropped.
  void send(const CanFrame& frame, std::int64_t t_ns) override;
  std::optional<CanFrame> receive(int timeout_ms) override;
  bool can_receive() const override { return true; }
  std::string describe() const override;

  std::uint16_t bound_port() const { return bound_.port; }
  const net::HostPort& bound_address() const { return bound_; }
  std::size_t connected_clients() const;
  // Clients that receive frames now (rawmode, start delay over).
  std::size_t streaming_clients() const;
  SocketcandServerStats stats() const;

  // Closes all connections and stops the I/O thread; receive() then returns nullopt.
  void stop();

 private:
  struct Client;
  void run();
  void wake();
  // all below run with mu_ held
  void accept_clients(std::vector<std::string>& warnings);
  void expire_handshakes(std::vector<std::string>& warnings);
  void read_client(Client& c, std::vector<std::string>& warnings, bool& queued);
  void handle_element(Client& c, const std::string& element, std::vector<std::string>& warnings,
                      bool& queued);
  void reply(Client& c, const char* text, std::size_t size, std::vector<std::string>* warnings);
  void flush_backlog(Client& c);
  void drop_client(Client& c, std::string_view why, std::vector<std::string>* warnings);
  void emit(const std::vector<std::string>& warnings) const;
  std::string slow_reason(std::uint64_t frames_lost) const;
  // Drops a client whose backlog overflowed: counted, with the frames it never received.
  void drop_slow_client(Client& c, std::vector<std::string>* warnings);

  SocketcandServerOptions options_;
  net::HostPort bound_;
  net::UniqueFd listen_fd_;
  net::UniqueFd wake_read_;
  net::UniqueFd wake_write_;

  mutable std::mutex mu_;  // clients_, stats_ (except the receive counters), stopping_
  std::vector<std::unique_ptr<Client>> clients_;
  SocketcandServerStats stats_;
  bool stopping_ = false;

  mutable std::mutex rx_mu_;  // rx_queue_ and the receive counters
  std::condition_variable rx_cv_;
  std::deque<CanFrame> rx_queue_;
  bool rx_closed_ = false;
  std::uint64_t stats_frames_received_ = 0;
  std::uint64_t stats_rx_overflows_ = 0;

  std::thread thread_;
};

}  // namespace sonarloop::can
