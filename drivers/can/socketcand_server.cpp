#include "drivers/can/socketcand_server.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "drivers/can/socketcand_protocol.h"
#include "drivers/net/tcp_listener.h"

namespace sonarloop::can {
namespace {

using Clock = std::chrono::steady_clock;  // I/O pacing only (start delay, handshake timeout)

constexpr char kHi[] = "< hi >";
constexpr char kOk[] = "< ok >";
constexpr char kEcho[] = "< echo >";
constexpr char kTooMany[] = "< error too many clients >";
constexpr char kExpectOpen[] = "< error expected '< open CHANNEL >' >";
constexpr char kModeUnsupported[] = "< error only rawmode is supported >";
constexpr char kUnknownCommand[] = "< error unknown command >";
constexpr char kBadSend[] = "< error malformed send >";
constexpr std::size_t kReadChunk = 4096;

bool would_block(int err) {
  return err == EAGAIN || err == EWOULDBLOCK;
}

}  // namespace

// A fixed-capacity FIFO of bytes (allocated once per client). Outside the anonymous namespace:
// Client, a member of the public class, holds one (GCC's -Wsubobject-linkage in a unity build).
class ByteRing {
 public:
  explicit ByteRing(std::size_t capacity) : buf_(capacity) {}
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  bool push(const char* data, std::size_t n) {
    if (n > buf_.size() - size_) return false;
    std::size_t tail = (head_ + size_) % buf_.size();
    const std::size_t first = std::min(n, buf_.size() - tail);
    std::memcpy(buf_.data() + tail, data, first);
    std::memcpy(buf_.data(), data + first, n - first);
    size_ += n;
    return true;
  }
  // The contiguous bytes at the front.
  const char* front(std::size_t& n) const {
    n = std::min(size_, buf_.size() - head_);
    return buf_.data() + head_;
  }
  void pop(std::size_t n) {
    head_ = (head_ + n) % buf_.size();
    size_ -= n;
    if (size_ == 0) head_ = 0;
  }

 private:
  std::vector<char> buf_;
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

struct SocketcandServer::Client {
  enum class State { kAwaitOpen, kAwaitMode, kRawPending, kRaw };
  Client(int fd_in, std::string peer_in, std::size_t backlog_bytes)
      : fd(fd_in), peer(std::move(peer_in)), backlog(backlog_bytes) {}
  net::UniqueFd fd;
  std::string peer;
  State state = State::kAwaitOpen;
  Clock::time_point open_by{};  // handshake deadline while in kAwaitOpen
  Clock::time_point raw_at{};
  SocketcandStreamParser parser;
  ByteRing backlog;
  bool dead = false;
  // Frame accounting, for frames_dropped_slow: frames handed to this client by send(), frames
  // whose first byte reached the kernel (every frame's text starts with its '\n', and only a
  // frame's text holds one), and whether the bytes given to the kernel so far end inside a frame
  // (a '\n' not yet followed by the frame's closing '>').
  std::uint64_t frames_handed = 0;
  std::uint64_t frames_begun = 0;
  bool mid_frame = false;
  // Accounts for bytes [p, p + n) given to the kernel.
  void note_written(const char* p, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      if (p[i] == '\n') {
        ++frames_begun;
        mid_frame = true;
      } else if (p[i] == '>') {
        mid_frame = false;
      }
    }
  }
  // Frames handed to this client that it will never receive whole.
  std::uint64_t frames_undelivered() const {
    return frames_handed - frames_begun + (mid_frame ? 1 : 0);
  }
};

SocketcandServer::SocketcandServer(const net::HostPort& listen_address,
                                   SocketcandServerOptions options)
    : options_(std::move(options)), bound_(listen_address) {
  if (options_.client_backlog_bytes < 1024) options_.client_backlog_bytes = 1024;
  const std::string where = net::to_string(listen_address);
  // SOMAXCONN: with an accept queue of 16, 50 clients connecting at once waited for the kernel's
  // SYN-ACK retries past their timeout (issue 11 section 4; the 50-client test)
  listen_fd_ = net::listen_tcp(listen_address);
  if (!listen_fd_.valid()) {
    const int err = errno;
    std::string hint;
    if (err == EADDRINUSE)
      hint =
          " (another socketcand server or sonarloop instance is using it; choose another "
          "port with --can socketcand:HOST:PORT)";
    throw std::runtime_error("socketcand server: cannot listen on " + where + ": " +
                             net::errno_text(err) + hint);
  }
  bound_.port = net::to_host_port(net::local_address(listen_fd_.get())).port;

  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0)
    throw std::runtime_error("socketcand server: pipe() failed: " + net::errno_text(errno));
  wake_read_.reset(pipe_fds[0]);
  wake_write_.reset(pipe_fds[1]);
  net::set_nonblocking(wake_read_.get());
  net::set_nonblocking(wake_write_.get());
  ::fcntl(wake_read_.get(), F_SETFD, FD_CLOEXEC);
  ::fcntl(wake_write_.get(), F_SETFD, FD_CLOEXEC);

  thread_ = std::thread([this] { run(); });
}

SocketcandServer::~SocketcandServer() {
  stop();
}

void SocketcandServer::stop() {
  {
    std::lock_guard lock(mu_);
    if (stopping_) return;
    stopping_ = true;
  }
  wake();
  if (thread_.joinable()) thread_.join();
  {
    std::lock_guard lock(mu_);
    clients_.clear();
    listen_fd_.reset();
  }
  {
    std::lock_guard lock(rx_mu_);
    rx_closed_ = true;
  }
  rx_cv_.notify_all();
}

std::string SocketcandServer::describe() const {
  return "socketcand server on " + net::to_string(bound_) + " (channel " + options_.channel + ")";
}

void SocketcandServer::wake() {
  const char b = 1;
  // a full pipe already guarantees a wake-up
  [[maybe_unused]] const ssize_t n = ::write(wake_write_.get(), &b, 1);
}

void SocketcandServer::emit(const std::vector<std::string>& warnings) const {
  for (const std::string& w : warnings) {
    if (options_.on_warning) {
      options_.on_warning(w);
    } else {
      std::fprintf(stderr, "warning: %s\n", w.c_str());
    }
  }
}

std::string SocketcandServer::slow_reason(std::uint64_t frames_lost) const {
  return "too slow (backlog full, limit " + std::to_string(options_.client_backlog_bytes) +
         " bytes; " + std::to_string(frames_lost) + " frames it did not receive)";
}

void SocketcandServer::drop_slow_client(Client& c, std::vector<std::string>* warnings) {
  const std::uint64_t lost = c.frames_undelivered();
  ++stats_.clients_dropped_slow;
  stats_.frames_dropped_slow += lost;
  drop_client(c, slow_reason(lost), warnings);
}

void SocketcandServer::drop_client(Client& c, std::string_view why,
                                   std::vector<std::string>* warnings) {
  if (c.dead) return;
  c.dead = true;
  ::shutdown(c.fd.get(), SHUT_RDWR);
  if (warnings)
    warnings->push_back(describe() + ": dropped client " + c.peer + ": " + std::string(why));
}

void SocketcandServer::flush_backlog(Client& c) {
  while (!c.dead && !c.backlog.empty()) {
    std::size_t n = 0;
    const char* p = c.backlog.front(n);
    const ssize_t sent = ::send(c.fd.get(), p, n, MSG_DONTWAIT | MSG_NOSIGNAL);
    if (sent < 0) {
      if (errno == EINTR) continue;
      if (!would_block(errno)) {
        ++stats_.clients_disconnected;
        drop_client(c, "connection lost", nullptr);
      }
      return;
    }
    c.note_written(p, static_cast<std::size_t>(sent));
    c.backlog.pop(static_cast<std::size_t>(sent));
    if (static_cast<std::size_t>(sent) < n) return;  // kernel buffer full
  }
}

void SocketcandServer::reply(Client& c, const char* text, std::size_t size,
                             std::vector<std::string>* warnings) {
  if (c.dead) return;
  std::size_t done = 0;
  if (c.backlog.empty()) {
    for (;;) {
      const ssize_t sent = ::send(c.fd.get(), text, size, MSG_DONTWAIT | MSG_NOSIGNAL);
      if (sent >= 0) {
        done = static_cast<std::size_t>(sent);
        c.note_written(text, done);
        break;
      }
      if (errno == EINTR) continue;
      if (!would_block(errno)) {
        ++stats_.clients_disconnected;
        drop_client(c, "connection lost", nullptr);
        return;
      }
      break;
    }
  }
  if (done == size) return;
  if (!c.backlog.push(text + done, size - done)) drop_slow_client(c, warnings);
}

void SocketcandServer::send(const CanFrame& frame, std::int64_t t_ns) {
  char msg[96];
  const std::size_t n = format_socketcand_frame(frame, t_ns, msg, sizeof msg);
  std::vector<std::string> warnings;  // stays empty (no allocation) unless a client is dropped
  bool need_wake = false;
  {
    std::lock_guard lock(mu_);
    ++stats_.frames_sent;
    for (auto& cp : clients_) {
      Client& c = *cp;
      if (c.dead) continue;
      if (c.state == Client::State::kRaw || c.state == Client::State::kRawPending) {
        const bool was_empty = c.backlog.empty();
        ++c.frames_handed;
        if (c.state == Client::State::kRaw) {
          reply(c, msg, n, &warnings);
        } else if (!c.backlog.push(msg, n)) {  // start delay: queue until it is over
          drop_slow_client(c, &warnings);
        }
        // the I/O thread must watch for POLLOUT (new backlog) or close a dropped client
        if (c.dead || (was_empty && !c.backlog.empty())) need_wake = true;
      }
    }
  }
  if (need_wake) wake();
  emit(warnings);
}

std::optional<CanFrame> SocketcandServer::receive(int timeout_ms) {
  std::unique_lock lock(rx_mu_);
  const auto ready = [this] { return !rx_queue_.empty() || rx_closed_; };
  if (timeout_ms < 0) {
    rx_cv_.wait(lock, ready);
  } else if (!rx_cv_.wait_for(lock, std::chrono::milliseconds(timeout_ms), ready)) {
    return std::nullopt;
  }
  if (rx_queue_.empty()) return std::nullopt;
  const CanFrame f = rx_queue_.front();
  rx_queue_.pop_front();
  return f;
}

std::size_t SocketcandServer::connected_clients() const {
  std::lock_guard lock(mu_);
  return static_cast<std::size_t>(
      std::count_if(clients_.begin(), clients_.end(), [](const auto& c) { return !c->dead; }));
}

std::size_t SocketcandServer::streaming_clients() const {
  std::lock_guard lock(mu_);
  return static_cast<std::size_t>(
      std::count_if(clients_.begin(), clients_.end(),
                    [](const auto& c) { return !c->dead && c->state == Client::State::kRaw; }));
}

SocketcandServerStats SocketcandServer::stats() const {
  SocketcandServerStats s;
  {
    std::lock_guard lock(mu_);
    s = stats_;
  }
  std::lock_guard lock(rx_mu_);
  s.frames_received = stats_frames_received_;
  s.receive_queue_overflows = stats_rx_overflows_;
  return s;
}

void SocketcandServer::accept_clients(std::vector<std::string>& warnings) {
  for (;;) {
    sockaddr_storage peer{};
    socklen_t len = sizeof peer;
    const int fd = ::accept(listen_fd_.get(), reinterpret_cast<sockaddr*>(&peer), &len);
    if (fd < 0) {
      if (errno == EINTR || errno == ECONNABORTED) continue;
      if (!would_block(errno))
        warnings.push_back(describe() + ": accept failed: " + net::errno_text(errno));
      return;
    }
    net::UniqueFd owned(fd);
    ::fcntl(fd, F_SETFD, FD_CLOEXEC);
    net::set_nonblocking(fd);
    const int one = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);  // one frame, one segment
    net::SocketAddress pa;
    std::memcpy(&pa.storage, &peer, sizeof peer);
    pa.length = len;
    const std::string peer_name = net::to_string(net::to_host_port(pa));
    auto live = static_cast<std::size_t>(
        std::count_if(clients_.begin(), clients_.end(), [](const auto& c) { return !c->dead; }));
    if (live >= options_.max_clients) {
      // make room by evicting the oldest client that has not opened the bus yet (clients_ is
      // in connection order)
      const auto pending = std::find_if(clients_.begin(), clients_.end(), [](const auto& c) {
        return !c->dead && c->state == Client::State::kAwaitOpen;
      });
      if (pending != clients_.end()) {
        ++stats_.clients_dropped_handshake;
        drop_client(**pending, "evicted for a new connection: no '< open CHANNEL >' yet",
                    &warnings);
        --live;
      }
    }
    if (live >= options_.max_clients) {
      ++stats_.clients_rejected;
      [[maybe_unused]] const ssize_t n =
          ::send(fd, kTooMany, sizeof kTooMany - 1, MSG_DONTWAIT | MSG_NOSIGNAL);
      warnings.push_back(describe() + ": rejected client " + peer_name + ": already " +
                         std::to_string(options_.max_clients) + " clients with the bus open");
      continue;  // owned closes it
    }
    ++stats_.clients_accepted;
    auto c = std::make_unique<Client>(owned.get(), peer_name, options_.client_backlog_bytes);
    static_cast<void>(owned.release());
    c->open_by = Clock::now() + std::chrono::milliseconds(options_.handshake_timeout_ms);
    reply(*c, kHi, sizeof kHi - 1, &warnings);
    clients_.push_back(std::move(c));
  }
}

void SocketcandServer::expire_handshakes(std::vector<std::string>& warnings) {
  if (options_.handshake_timeout_ms <= 0) return;
  const auto now = Clock::now();
  for (auto& c : clients_) {
    if (!c->dead && c->state == Client::State::kAwaitOpen && c->open_by <= now) {
      ++stats_.clients_dropped_handshake;
      drop_client(*c,
                  "no '< open CHANNEL >' within " + std::to_string(options_.handshake_timeout_ms) +
                      " ms of connecting",
                  &warnings);
    }
  }
}

void SocketcandServer::handle_element(Client& c, const std::string& element,
                                      std::vector<std::string>& warnings, bool& queued) {
  const auto el = split_socketcand_element(element);
  const std::string_view cmd = el ? el->command : std::string_view{};
  if (cmd == "echo") {
    reply(c, kEcho, sizeof kEcho - 1, &warnings);
    return;
  }
  switch (c.state) {
    case Client::State::kAwaitOpen:
      if (cmd == "open" && el && !el->args.empty()) {
        reply(c, kOk, sizeof kOk - 1, &warnings);
        c.state = Client::State::kAwaitMode;
      } else {
        ++stats_.protocol_errors;
        reply(c, kExpectOpen, sizeof kExpectOpen - 1, &warnings);
      }
      return;
    case Client::State::kAwaitMode:
      if (cmd == "rawmode") {
        reply(c, kOk, sizeof kOk - 1, &warnings);
        c.state = Client::State::kRawPending;
        c.raw_at = Clock::now() + std::chrono::milliseconds(options_.rawmode_start_delay_ms);
        return;
      }
      if (cmd == "bcmmode") {  // already in BCM mode after open
        reply(c, kOk, sizeof kOk - 1, &warnings);
        return;
      }
      if (cmd == "controlmode" || cmd == "isotpmode") {
        ++stats_.protocol_errors;
        reply(c, kModeUnsupported, sizeof kModeUnsupported - 1, &warnings);
        return;
      }
      break;  // "send" is valid in BCM mode too
    case Client::State::kRawPending:
    case Client::State::kRaw:
      if (cmd == "rawmode") return;  // already there
      break;
  }
  if (cmd == "send") {
    std::string error;
    const auto frame = parse_socketcand_send(element, error);
    if (!frame) {
      ++stats_.protocol_errors;
      warnings.push_back(describe() + ": client " + c.peer + ": " + error + " in '" + element +
                         "'");
      if (c.state == Client::State::kAwaitMode) reply(c, kBadSend, sizeof kBadSend - 1, &warnings);
      return;
    }
    {
      std::lock_guard lock(rx_mu_);
      if (rx_queue_.size() >= options_.receive_queue_frames) {
        rx_queue_.pop_front();
        ++stats_rx_overflows_;
      }
      rx_queue_.push_back(*frame);
      ++stats_frames_received_;
    }
    queued = true;
    return;
  }
  ++stats_.protocol_errors;
  if (c.state == Client::State::kAwaitMode)
    reply(c, kUnknownCommand, sizeof kUnknownCommand - 1, &warnings);
}

void SocketcandServer::read_client(Client& c, std::vector<std::string>& warnings, bool& queued) {
  char buf[kReadChunk];
  while (!c.dead) {
    const ssize_t n = ::recv(c.fd.get(), buf, sizeof buf, MSG_DONTWAIT);
    if (n < 0) {
      if (errno == EINTR) continue;
      if (would_block(errno)) return;
      ++stats_.clients_disconnected;
      drop_client(c, "connection lost", nullptr);
      return;
    }
    if (n == 0) {  // the client closed its side
      ++stats_.clients_disconnected;
      drop_client(c, "closed", nullptr);
      return;
    }
    c.parser.append(buf, static_cast<std::size_t>(n));
    std::string error;
    while (auto element = c.parser.next(error))
      handle_element(c, *element, warnings, queued);
    if (!error.empty()) {
      ++stats_.protocol_errors;
      drop_client(c, "protocol error: " + error, &warnings);
      return;
    }
  }
}

void SocketcandServer::run() {
  std::vector<pollfd> fds;
  std::vector<std::string> warnings;
  for (;;) {
    int timeout_ms = -1;
    {
      std::lock_guard lock(mu_);
      if (stopping_) return;
      // forget closed clients
      std::erase_if(clients_, [](const auto& c) { return c->dead; });
      fds.clear();
      fds.push_back({wake_read_.get(), POLLIN, 0});
      fds.push_back({listen_fd_.get(), POLLIN, 0});
      const auto now = Clock::now();
      for (const auto& c : clients_) {
        short events = POLLIN;
        // a client in its start delay keeps its backlog until the delay is over
        if (c->state != Client::State::kRawPending && !c->backlog.empty()) events |= POLLOUT;
        fds.push_back({c->fd.get(), events, 0});
        const bool timed_open =
            c->state == Client::State::kAwaitOpen && options_.handshake_timeout_ms > 0;
        if (c->state == Client::State::kRawPending || timed_open) {
          const auto at = c->state == Client::State::kRawPending ? c->raw_at : c->open_by;
          const auto wait = std::chrono::ceil<std::chrono::milliseconds>(at - now).count();
          const int ms = static_cast<int>(std::max<std::int64_t>(0, wait));
          timeout_ms = timeout_ms < 0 ? ms : std::min(timeout_ms, ms);
        }
      }
    }
    const int ready = ::poll(fds.data(), fds.size(), timeout_ms);
    if (ready < 0 && errno != EINTR) {
      emit({describe() + ": poll failed: " + net::errno_text(errno)});
      return;
    }
    bool queued = false;
    warnings.clear();
    {
      std::lock_guard lock(mu_);
      if (stopping_) return;
      if (fds[0].revents & POLLIN) {
        char drain[64];
        while (::read(wake_read_.get(), drain, sizeof drain) > 0) {
        }
      }
      // clients_ only grows at its end between the poll set and here (only this thread edits it)
      for (std::size_t i = 2; i < fds.size(); ++i) {
        Client& c = *clients_[i - 2];
        if (c.dead) continue;
        if (fds[i].revents & (POLLIN | POLLHUP | POLLERR)) read_client(c, warnings, queued);
        if (fds[i].revents & POLLOUT) flush_backlog(c);
      }
      expire_handshakes(warnings);
      if (fds[1].revents & POLLIN) accept_clients(warnings);
      const auto now = Clock::now();
      for (auto& c : clients_) {
        if (!c->dead && c->state == Client::State::kRawPending && c->raw_at <= now) {
          c->state = Client::State::kRaw;
          flush_backlog(*c);  // frames sent during the start delay
        }
      }
    }
    if (queued) rx_cv_.notify_all();
    emit(warnings);
  }
}

}  // namespace sonarloop::can
