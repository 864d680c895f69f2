#include "drivers/can/socketcand_client.h"

#include <cerrno>
#include <chrono>
#include <stdexcept>

#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>

namespace sonarloop::can {
namespace {

using Clock = std::chrono::steady_clock;  // I/O timeouts only

int remaining_ms(Clock::time_point deadline) {
  const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return static_cast<int>(std::max<std::int64_t>(0, left));
}

}  // namespace

SocketcandClient::SocketcandClient(const net::HostPort& server, SocketcandClientOptions options)
    : server_(server), options_(std::move(options)) {
  const net::SocketAddress addr = net::resolve(server);
  fd_.reset(::socket(addr.family(), SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
  if (!fd_.valid())
    throw std::runtime_error(describe() + ": socket() failed: " + net::errno_text(errno));
  // non-blocking connect, bounded by the timeout
  if (::connect(fd_.get(), addr.get(), addr.length) != 0) {
    if (errno != EINPROGRESS)
      throw std::runtime_error(describe() + ": cannot connect: " + net::errno_text(errno));
    pollfd p{fd_.get(), POLLOUT, 0};
    const int ready = ::poll(&p, 1, options_.timeout_ms);
    if (ready <= 0)
      throw std::runtime_error(describe() + ": cannot connect: no answer within " +
                               std::to_string(options_.timeout_ms) + " ms");
    int err = 0;
    socklen_t len = sizeof err;
    ::getsockopt(fd_.get(), SOL_SOCKET, SO_ERROR, &err, &len);
    if (err != 0)
      throw std::runtime_error(describe() + ": cannot connect: " + net::errno_text(err));
  }
  const int one = 1;
  ::setsockopt(fd_.get(), IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  connected_ = true;

  expect("< hi >", "greeting");
  const std::string open = "< open " + options_.channel + " >";
  {
    std::lock_guard lock(send_mu_);
    if (::send(fd_.get(), open.data(), open.size(), MSG_NOSIGNAL) !=
        static_cast<ssize_t>(open.size()))
      throw std::runtime_error(describe() + ": sending open failed: " + net::errno_text(errno));
  }
  expect("< ok >", "open");
  const std::string raw = "< rawmode >";
  {
    std::lock_guard lock(send_mu_);
    if (::send(fd_.get(), raw.data(), raw.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(raw.size()))
      throw std::runtime_error(describe() + ": sending rawmode failed: " + net::errno_text(errno));
  }
  expect("< ok >", "rawmode");
}

std::string SocketcandClient::describe() const {
  return "socketcand client of " + net::to_string(server_) + " (channel " + options_.channel + ")";
}

void SocketcandClient::expect(const char* what, const char* step) {
  const auto element = next_element(options_.timeout_ms);
  if (!element)
    throw std::runtime_error(describe() + ": no reply to " + step + " within " +
                             std::to_string(options_.timeout_ms) + " ms (expected '" + what + "')");
  const auto got = split_socketcand_element(*element);
  const auto want = split_socketcand_element(what);
  if (!got || got->command != want->command)
    throw std::runtime_error(describe() + ": " + step + " failed: expected '" + what + "', got '" +
                             *element + "'");
}

bool SocketcandClient::read_some(int timeout_ms) {
  pollfd p{fd_.get(), POLLIN, 0};
  const int ready = ::poll(&p, 1, timeout_ms < 0 ? -1 : timeout_ms);
  if (ready < 0) {
    if (errno == EINTR) return false;
    throw std::runtime_error(describe() + ": poll failed: " + net::errno_text(errno));
  }
  if (ready == 0) return false;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::recv(fd_.get(), buf, sizeof buf, MSG_DONTWAIT);
    if (n > 0) {
      parser_.append(buf, static_cast<std::size_t>(n));
      if (static_cast<std::size_t>(n) < sizeof buf) return true;
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return true;
    connected_ = false;
    throw std::runtime_error(describe() + ": connection closed by the server" +
                             (n < 0 ? " (" + net::errno_text(errno) + ")" : std::string()));
  }
}

std::optional<std::string> SocketcandClient::next_element(int timeout_ms) {
  const auto deadline = Clock::now() + std::chrono::milliseconds(std::max(timeout_ms, 0));
  for (;;) {
    std::string error;
    if (auto element = parser_.next(error)) return element;
    if (!error.empty()) {
      connected_ = false;
      throw std::runtime_error(describe() + ": protocol error: " + error);
    }
    if (!connected_) throw std::runtime_error(describe() + ": connection closed by the server");
    const int wait = timeout_ms < 0 ? -1 : remaining_ms(deadline);
    if (!read_some(wait) && timeout_ms >= 0 && Clock::now() >= deadline) return std::nullopt;
  }
}

std::optional<TimedCanFrame> SocketcandClient::receive_timed(int timeout_ms) {
  const auto deadline = Clock::now() + std::chrono::milliseconds(std::max(timeout_ms, 0));
  for (;;) {
    const int wait = timeout_ms < 0 ? -1 : remaining_ms(deadline);
    const auto element = next_element(wait);
    if (!element) return std::nullopt;
    const auto el = split_socketcand_element(*element);
    if (el && el->command == "frame") {
      std::string error;
      if (auto frame = parse_socketcand_frame(*element, error)) return frame;
    }
    ++errors_;  // "< error ... >", a malformed frame or an unexpected element
    if (timeout_ms >= 0 && Clock::now() >= deadline) return std::nullopt;
  }
}

std::optional<CanFrame> SocketcandClient::receive(int timeout_ms) {
  const auto f = receive_timed(timeout_ms);
  if (!f) return std::nullopt;
  return f->frame;
}

void SocketcandClient::send(const CanFrame& frame, std::int64_t /*t_ns*/) {
  char msg[64];
  const std::size_t n = format_socketcand_send(frame, msg, sizeof msg);
  std::lock_guard lock(send_mu_);
  std::size_t done = 0;
  while (done < n) {
    const ssize_t sent = ::send(fd_.get(), msg + done, n - done, MSG_NOSIGNAL);
    if (sent > 0) {
      done += static_cast<std::size_t>(sent);
      continue;
    }
    if (sent < 0 && errno == EINTR) continue;
    if (sent < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      pollfd p{fd_.get(), POLLOUT, 0};
      if (::poll(&p, 1, options_.timeout_ms) > 0) continue;
      throw std::runtime_error(describe() + ": send timed out after " +
                               std::to_string(options_.timeout_ms) + " ms");
    }
    connected_ = false;
    throw std::runtime_error(describe() + ": send failed: " + net::errno_text(errno));
  }
}

}  // namespace sonarloop::can
