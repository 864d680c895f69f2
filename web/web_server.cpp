#include "web/web_server.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include "drivers/net/tcp_listener.h"
#include "drivers/net/unique_fd.h"
#include "web/web_page.h"

namespace sonarloop::web {
namespace {

using Clock = std::chrono::steady_clock;  // I/O deadlines only

// A quiet stream sends a comment line this often: it keeps proxies and the browser from timing
// out, and a write to a vanished browser fails, which ends its stream.
constexpr std::chrono::milliseconds kIdleCommentEvery{1000};
// The loop looks at its deadlines at least this often.
constexpr std::chrono::milliseconds kLongestPoll{1000};
// Events are taken from a stream's queue while less than this waits to be sent: the rest stays
// in the hub's bounded queue, which drops its oldest when full.
constexpr std::size_t kStreamBufferBytes = 64 * 1024;
// Bytes read per recv. A stream's connection has what its browser sends read and dropped, at
// most kDropBytes per wake. A connection closing after its response (a refused request, or
// Connection: close) has up to kLingerBytes read and dropped for up to kLinger once the
// response has gone, before it is closed: a close with unread bytes resets the connection,
// and the reset can destroy the response before the client reads it.
constexpr std::size_t kReadChunk = 4096;
constexpr std::size_t kDropBytes = 64 * 1024;
constexpr std::size_t kLingerBytes = 256 * 1024;
constexpr std::chrono::milliseconds kLinger{500};
// At the cap, a connection may be replaced by a new one once it has waited this long for a
// request (a browser sends its request at once); the loop looks again this often.
constexpr std::chrono::milliseconds kEvictAfter{1000};
constexpr std::chrono::milliseconds kFullPoll{100};
// Pipelined requests answered per wake of one connection (the others' turn comes between).
constexpr int kRequestsPerWake = 16;

constexpr char kSecurityHeaders[] =
    "Cache-Control: no-store\r\n"
    "X-Content-Type-Options: nosniff\r\n"
    "Content-Security-Policy: default-src 'none'; script-src 'unsafe-inline'; style-src "
    "'unsafe-inline'; connect-src 'self'; img-src 'self' data:\r\n";

const char* reason_phrase(int status) {
  switch (status) {
    case 200:
      return "OK";
    case 400:
      return "Bad Request";
    case 404:
      return "Not Found";
    case 405:
      return "Method Not Allowed";
    case 408:
      return "Request Timeout";
    case 413:
      return "Content Too Large";
    case 431:
      return "Request Header Fields Too Large";
    case 503:
      return "Service Unavailable";
    case 505:
      return "HTTP Version Not Supported";
    default:
      return "Error";
  }
}

// A whole response with a body of known length.
std::string response(int status, std::string_view type, std::string_view body, bool keep_alive,
                     bool head_only, std::string_view extra_headers = {}) {
  std::string r = "HTTP/1.1 " + std::to_string(status) + " " + reason_phrase(status) + "\r\n";
  r += "Content-Type: ";
  r += type;
  r += "\r\nContent-Length: " + std::to_string(body.size()) + "\r\n";
  r += kSecurityHeaders;
  r += extra_headers;
  r += keep_alive ? "Connection: keep-alive\r\n\r\n" : "Connection: close\r\n\r\n";
  if (!head_only) r += body;
  return r;
}

std::string error_response(int status, std::string_view why, std::string_view extra = {}) {
  std::string body = std::to_string(status) + " " + reason_phrase(status);
  if (!why.empty()) {
    body += ": ";
    body += why;
  }
  body += "\n";
  return response(status, "text/plain; charset=utf-8", body, false, false, extra);
}

}  // namespace

struct WebServer::Impl {
  // one client's connection: what it sent, what goes back, its deadlines
  struct Connection {
    net::UniqueFd fd;
    std::string in;   // received, not yet answered
    std::string out;  // to send, from `sent` on
    std::size_t sent = 0;
    Clock::time_point ready_since;    // reading: since the connection opened or last answered
    Clock::time_point deadline;       // reading: the request head must be whole by then
    Clock::time_point last_progress;  // writing: the peer last took bytes then
    Clock::time_point last_event;     // a stream: the last bytes queued
    Clock::time_point linger_until;   // closing: the peer may still be sending until then
    std::size_t linger_bytes_left = kLingerBytes;
    std::shared_ptr<WebClient> stream;
    bool closing = false;    // close once `out` has gone
    bool lingering = false;  // `out` has gone, the write side is shut; dropping what comes
    bool peer_done = false;  // the peer shut its write side
    bool dead = false;
    bool check_head = true;  // bytes with a line end (or past the limit) came since the last parse

    std::size_t pending() const { return out.size() - sent; }
    bool reading() const { return !stream && !closing && pending() == 0; }
  };

  Impl(WebHub& h, const WebServerOptions& o) : hub(h), options(o) {}

  void run();
  void accept_all(Clock::time_point now);
  bool full() const;
  Connection* evictable(Clock::time_point now) const;
  void service(Connection& c, short revents, Clock::time_point now);
  void read_some(Connection& c);
  bool answer_requests(Connection& c, Clock::time_point now);
  void answer(Connection& c, const net::HttpRequestHead& head, Clock::time_point now);
  void refuse(Connection& c, int status, std::string_view why, std::string_view extra = {});
  void fill_stream(Connection& c, Clock::time_point now);
  void write_some(Connection& c, Clock::time_point now);
  void check_deadlines(Connection& c, Clock::time_point now);
  void finish(Connection& c);
  void flush_at_stop();
  std::chrono::milliseconds poll_timeout(Clock::time_point now) const;
  void count(std::uint64_t WebServerCounters::*field) {
    std::lock_guard lock(mutex);
    ++(counters.*field);
  }

  WebHub& hub;
  const WebServerOptions options;
  net::UniqueFd listen_fd;
  std::shared_ptr<net::UniqueFd> wake_fd;  // an eventfd: shared with the clients' wake calls
  net::HostPort bound;
  std::vector<std::unique_ptr<Connection>> connections;  // in the order they opened
  std::atomic<bool> stopping{false};
  std::thread thread;
  mutable std::mutex mutex;
  WebServerCounters counters;
  bool stopped = false;  // guarded by `mutex`
};

std::chrono::milliseconds WebServer::Impl::poll_timeout(Clock::time_point now) const {
  Clock::time_point next = now + kLongestPoll;
  for (const auto& c : connections) {
    if (c->lingering) {
      next = std::min(next, c->linger_until);
    } else if (c->pending() > 0) {
      next = std::min(next, c->last_progress + options.write_timeout);
    } else if (c->stream) {
      next = std::min(next, c->last_event + kIdleCommentEvery);
    } else if (c->reading()) {
      next = std::min(next, c->check_head && !c->in.empty() ? now : c->deadline);
    }
  }
  const auto wait = std::chrono::ceil<std::chrono::milliseconds>(next - now);
  return std::max(wait, std::chrono::milliseconds(0));
}

void WebServer::Impl::run() {
  std::vector<pollfd> fds;
  while (!stopping.load()) {
    fds.clear();
    fds.push_back({wake_fd->get(), POLLIN, 0});
    // at the cap with none to replace, new connections wait in the kernel's accept queue
    const bool accepting = !full() || evictable(Clock::now());
    fds.push_back({listen_fd.get(), static_cast<short>(accepting ? POLLIN : 0), 0});
    for (const auto& c : connections) {
      short events = 0;
      if (c->pending() > 0) events |= POLLOUT;
      // a connection with a response on its way is not read: pipelined requests wait in the
      // kernel's buffers, not in ours; a stream is read only to notice the browser leave
      if (c->pending() == 0 && !c->peer_done) events |= POLLIN;
      fds.push_back({c->fd.get(), events, 0});
    }
    auto timeout = poll_timeout(Clock::now());
    if (!accepting) timeout = std::min(timeout, kFullPoll);
    const int timeout_ms = static_cast<int>(timeout.count());
    if (::poll(fds.data(), fds.size(), timeout_ms) < 0 && errno != EINTR) break;
    const Clock::time_point now = Clock::now();
    if (fds[0].revents & POLLIN) {
      std::uint64_t n = 0;
      [[maybe_unused]] const ssize_t r = ::read(wake_fd->get(), &n, sizeof n);
    }
    if (stopping.load()) break;
    // the connections polled are the first fds.size() - 2; those accepted below come after
    const std::size_t polled = fds.size() - 2;
    for (std::size_t i = 0; i < polled; ++i)
      service(*connections[i], fds[i + 2].revents, now);
    if (fds[1].revents & POLLIN) accept_all(now);
    for (auto& c : connections)
      if (c->dead) finish(*c);
    std::erase_if(connections, [](const auto& c) { return c->dead; });
  }
  flush_at_stop();
}

bool WebServer::Impl::full() const {
  return std::count_if(connections.begin(), connections.end(),
                       [](const auto& c) { return !c->dead; }) >= options.max_connections;
}

WebServer::Impl::Connection* WebServer::Impl::evictable(Clock::time_point now) const {
  Connection* oldest = nullptr;
  for (const auto& c : connections) {
    if (c->dead || !c->reading() || now - c->ready_since < kEvictAfter) continue;
    if (!oldest || c->ready_since < oldest->ready_since) oldest = c.get();
  }
  return oldest;
}

void WebServer::Impl::accept_all(Clock::time_point now) {
  for (;;) {
    // at the cap, a new connection takes the place of the one that has waited longest for its
    // request (a slow client, or a browser's idle keep-alive, which opens another when it
    // needs one); when none has waited kEvictAfter, the new ones wait in the accept queue
    Connection* replaced = full() ? evictable(now) : nullptr;
    if (full() && !replaced) return;
    net::UniqueFd fd(::accept4(listen_fd.get(), nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC));
    if (!fd.valid()) return;  // EAGAIN: none left; EMFILE and the like: tried again next wake
    if (replaced) {
      replaced->dead = true;
      count(&WebServerCounters::evicted);
    }
    auto c = std::make_unique<Connection>();
    c->fd = std::move(fd);
    c->last_progress = c->last_event = c->ready_since = now;
    c->deadline = now + options.request_timeout;
    connections.push_back(std::move(c));
    count(&WebServerCounters::connections);
  }
}

void WebServer::Impl::service(Connection& c, short revents, Clock::time_point now) {
  if (c.dead) return;
  if (revents & (POLLERR | POLLNVAL)) {
    c.dead = true;
    return;
  }
  if (revents & (POLLIN | POLLHUP)) read_some(c);
  if (c.dead) return;
  if (c.lingering) {
    if (c.peer_done || now >= c.linger_until || c.linger_bytes_left == 0) c.dead = true;
    return;
  }
  if (c.stream && c.peer_done) {  // the browser left
    c.dead = true;
    return;
  }
  // pipelined requests already received are answered while their responses go out at once; a
  // bounded number per wake, the rest at the next (poll_timeout returns at once for them)
  for (int i = 0; i < kRequestsPerWake; ++i) {
    const bool answered = answer_requests(c, now);
    fill_stream(c, now);
    write_some(c, now);
    if (!answered || c.dead || !c.reading()) break;
  }
  check_deadlines(c, now);
}

void WebServer::Impl::read_some(Connection& c) {
  char buf[kReadChunk];
  // a request head needs at most max_head_bytes + 1 bytes to be judged; a stream's or a
  // refused connection's bytes are dropped, a bounded number per wake
  const bool keep = c.reading();
  std::size_t budget = kDropBytes;
  if (keep) budget = options.max_head_bytes + 1 - std::min(c.in.size(), options.max_head_bytes + 1);
  if (c.lingering) budget = std::min(budget, c.linger_bytes_left);
  while (budget > 0) {
    const ssize_t n = ::recv(c.fd.get(), buf, std::min(budget, sizeof buf), MSG_DONTWAIT);
    if (n == 0) {
      c.peer_done = true;
      return;
    }
    if (n < 0) {
      if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) c.dead = true;
      return;
    }
    const auto got = static_cast<std::size_t>(n);
    if (keep) {
      c.in.append(buf, got);
      if (std::find(buf, buf + got, '\n') != buf + got) c.check_head = true;
    }
    budget -= got;
    if (c.lingering) c.linger_bytes_left -= got;
  }
  if (keep) c.check_head = true;  // the limit is reached: the parse says so
}

bool WebServer::Impl::answer_requests(Connection& c, Clock::time_point now) {
  // one at a time: the next pipelined request is answered once this response has gone
  if (!c.reading() || !c.check_head) {
    if (c.reading() && c.peer_done) c.dead = true;  // it said all it had to say
    return false;
  }
  c.check_head = false;
  net::HttpRequestHead head;
  std::string error;
  switch (net::parse_http_request_head(c.in, head, error, options.max_head_bytes)) {
    case net::HttpParse::kIncomplete:
      if (c.peer_done) c.dead = true;  // the peer ended mid-request
      return false;
    case net::HttpParse::kBad:
      refuse(c, 400, error);
      return true;
    case net::HttpParse::kTooLarge:
      refuse(c, 431, error);
      return true;
    case net::HttpParse::kVersion:
      refuse(c, 505, error);
      return true;
    case net::HttpParse::kComplete:
      break;
  }
  c.in.erase(0, head.head_bytes);
  c.check_head = true;  // more requests may have come with it
  count(&WebServerCounters::requests);
  answer(c, head, now);
  return true;
}

void WebServer::Impl::answer(Connection& c, const net::HttpRequestHead& head,
                             Clock::time_point now) {
  const bool head_only = head.method == "HEAD";
  if (head.method != "GET" && !head_only) {
    return refuse(c, 405, "this view is read-only: GET or HEAD", "Allow: GET, HEAD\r\n");
  }
  if (head.has_body) return refuse(c, 413, "a GET here takes no body");
  const bool keep_alive = head.keep_alive && !c.peer_done;
  if (head.path == "/") {
    c.out = response(200, "text/html; charset=utf-8", kWebPage, keep_alive, head_only);
  } else if (head.path == "/stats.json") {
    c.out = response(200, "application/json", hub.stats_json() + "\n", keep_alive, head_only);
  } else if (head.path == "/events") {
    std::shared_ptr<net::UniqueFd> wake = wake_fd;
    std::shared_ptr<WebClient> client = head_only ? nullptr : hub.subscribe([wake] {
      const std::uint64_t one = 1;
      [[maybe_unused]] const ssize_t r = ::write(wake->get(), &one, sizeof one);
    });
    if (!head_only && !client) {
      c.out =
          response(503, "text/plain; charset=utf-8",
                   "too many viewers of this run; close another page and reload\n", false, false);
      c.closing = true;
    } else {
      // the stream lasts until the run ends or the browser leaves: its end is the
      // connection's close
      c.out = std::string("HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\n") +
              kSecurityHeaders + "Connection: close\r\n\r\n";
      c.stream = std::move(client);
      c.closing = head_only;
      c.last_event = now;
    }
  } else {
    c.out = response(404, "text/plain; charset=utf-8",
                     "404: not served here (GET / for the page)\n", keep_alive, head_only);
  }
  c.sent = 0;
  if (!keep_alive) c.closing = true;
}

void WebServer::Impl::refuse(Connection& c, int status, std::string_view why,
                             std::string_view extra) {
  count(&WebServerCounters::bad_requests);
  c.out = error_response(status, why, extra);
  c.sent = 0;
  c.closing = true;
  c.in.clear();
}

void WebServer::Impl::fill_stream(Connection& c, Clock::time_point now) {
  if (!c.stream || c.closing) return;
  while (c.pending() < kStreamBufferBytes) {
    Event e;
    const WebClient::Next next = c.stream->next(e, std::chrono::milliseconds(0));
    if (next == WebClient::Next::kTimeout) break;
    if (next == WebClient::Next::kClosed) {  // the run ended: what is queued, then the close
      c.closing = true;
      break;
    }
    if (c.sent > 0) {  // what has gone makes room
      c.out.erase(0, c.sent);
      c.sent = 0;
    }
    c.out += *e;
    c.last_event = now;
  }
  if (c.pending() == 0 && !c.closing && now - c.last_event >= kIdleCommentEvery) {
    c.out = ": idle\n\n";
    c.sent = 0;
    c.last_event = now;
  }
}

void WebServer::Impl::write_some(Connection& c, Clock::time_point now) {
  const bool responding = c.pending() > 0;
  while (c.pending() > 0) {
    const ssize_t n =
        ::send(c.fd.get(), c.out.data() + c.sent, c.pending(), MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n < 0) {
      if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) c.dead = true;
      return;
    }
    c.sent += static_cast<std::size_t>(n);
    c.last_progress = now;
  }
  c.out.clear();
  c.sent = 0;
  if (c.closing && !c.lingering) {
    // shut the write side and drop what the peer still sends for a moment, so that the
    // response is not lost to the reset a close with unread bytes would cause
    ::shutdown(c.fd.get(), SHUT_WR);
    c.lingering = true;
    c.linger_until = now + kLinger;
  } else if (responding && !c.stream) {
    c.ready_since = now;  // the next request's time starts now
    c.deadline = now + options.request_timeout;
  }
}

void WebServer::Impl::check_deadlines(Connection& c, Clock::time_point now) {
  if (c.dead || c.lingering) return;
  if (c.pending() > 0) {
    if (now - c.last_progress >= options.write_timeout) {
      count(&WebServerCounters::timeouts);
      c.dead = true;
    }
  } else if (c.reading() && now >= c.deadline) {
    // best effort: a client that began a request learns why; an idle connection (a browser's
    // keep-alive or pre-connect) is just closed
    if (!c.in.empty()) {
      count(&WebServerCounters::timeouts);
      const std::string late = error_response(408, "the request did not come whole in time");
      [[maybe_unused]] const ssize_t n =
          ::send(c.fd.get(), late.data(), late.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
    }
    c.dead = true;
  }
}

void WebServer::Impl::finish(Connection& c) {
  if (c.stream) {
    hub.unsubscribe(c.stream);
    c.stream.reset();
  }
  c.fd.reset();
}

void WebServer::Impl::flush_at_stop() {
  listen_fd.reset();
  // the streams end after what is queued for them; the other connections after their response
  const Clock::time_point until = Clock::now() + options.stop_flush;
  for (auto& c : connections) {
    if (c->dead || c->lingering) {
      c->dead = true;
      continue;
    }
    if (c->stream) {
      c->stream->close();
      fill_stream(*c, Clock::now());
    }
    if (c->pending() == 0) c->dead = true;
  }
  std::vector<pollfd> fds;
  for (;;) {
    fds.clear();
    std::vector<Connection*> writing;
    for (auto& c : connections) {
      if (c->dead) continue;
      fds.push_back({c->fd.get(), POLLOUT, 0});
      writing.push_back(c.get());
    }
    const Clock::time_point now = Clock::now();
    if (writing.empty() || now >= until) break;
    const auto wait = std::chrono::ceil<std::chrono::milliseconds>(until - now);
    if (::poll(fds.data(), fds.size(), static_cast<int>(wait.count())) < 0 && errno != EINTR) {
      break;
    }
    for (std::size_t i = 0; i < writing.size(); ++i) {
      Connection& c = *writing[i];
      if (fds[i].revents & (POLLERR | POLLHUP | POLLNVAL)) {
        c.dead = true;
      } else if (fds[i].revents & POLLOUT) {
        write_some(c, Clock::now());
        if (c.pending() == 0) c.dead = true;
      }
    }
  }
  for (auto& c : connections)
    finish(*c);
  connections.clear();
}

WebServer::WebServer(WebHub& hub, const net::HostPort& address, const WebServerOptions& options)
    : impl_(std::make_unique<Impl>(hub, options)) {
  if (options.max_head_bytes < 256 || options.max_connections < 1 ||
      options.request_timeout.count() <= 0 || options.write_timeout.count() <= 0 ||
      options.stop_flush.count() < 0) {
    throw std::invalid_argument(
        "web server: the head limit must be at least 256 bytes, the connections and timeouts "
        "positive");
  }
  // no name lookups: "localhost" is the loopback address (drivers/net/host_port.h)
  const std::string host = address.host == "localhost" ? "127.0.0.1" : address.host;
  impl_->bound = {host, address.port};
  impl_->listen_fd = net::listen_tcp(impl_->bound);
  if (!impl_->listen_fd.valid()) {
    const int err = errno;
    throw std::runtime_error(
        "--web: cannot listen on " + net::to_string(address) + ": " + net::errno_text(err) +
        (err == EADDRINUSE ? " (another program or sonarloop run has it)" : ""));
  }
  impl_->bound.port = net::to_host_port(net::local_address(impl_->listen_fd.get())).port;
  impl_->wake_fd = std::make_shared<net::UniqueFd>(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC));
  if (!impl_->wake_fd->valid()) {
    throw std::runtime_error("--web: eventfd failed: " + net::errno_text(errno));
  }
  impl_->thread = std::thread([this] { impl_->run(); });
}

WebServer::~WebServer() {
  stop();
}

const net::HostPort& WebServer::address() const {
  return impl_->bound;
}

std::string WebServer::url() const {
  const net::HostPort& a = address();
  const bool v6 = a.host.find(':') != std::string::npos;
  return "http://" + (v6 ? "[" + a.host + "]" : a.host) + ":" + std::to_string(a.port) + "/";
}

WebServerCounters WebServer::counters() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->counters;
}

void WebServer::stop() {
  {
    std::lock_guard lock(impl_->mutex);
    if (impl_->stopped) return;
    impl_->stopped = true;
  }
  impl_->stopping.store(true);
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t r = ::write(impl_->wake_fd->get(), &one, sizeof one);
  if (impl_->thread.joinable()) impl_->thread.join();
}

}  // namespace sonarloop::web
