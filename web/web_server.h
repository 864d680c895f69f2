#pragma once
// The live operator view's HTTP server (docs/web.md): one thread and an event loop over
// non-blocking POSIX sockets, serving
//   GET /            the page (web/web_page.h): HTML, script and style inline, nothing
//                    fetched from elsewhere
//   GET /events      the hub's events as Server-Sent Events (text/event-stream), pushed as
//                    they come; a comment line every second keeps an idle stream alive and
//                    finds a vanished browser; at most WebHubOptions::max_clients at once (503)
//   GET /stats.json  the latest statistics with the hub's counters
// (HEAD of each too) and nothing else: other paths get 404, other methods 405. Read-only:
// nothing a browser sends changes the run.
//
// Bounded whatever a client does (docs/reliability.md, issue 29):
//   - a request head (request line and header fields) is at most max_head_bytes and
//     kMaxHttpHeaderFields fields (431 beyond), and must be complete within request_timeout of
//     the connection's opening or of the previous response (408 after): a client that sends a
//     byte at a time holds a connection for request_timeout, not for ever;
//   - requests with a body are refused (413): nothing here takes one;
//   - a connection whose peer takes none of the response for write_timeout is closed; a stream
//     whose browser stops reading loses its oldest events in the hub (WebClient), the server
//     holds at most about kStreamBufferBytes for it;
//   - at most max_connections connections; at the cap, a new connection takes the place of the
//     one that has waited longest (at least a second) for its request, or waits in the kernel's
//     accept queue (SOMAXCONN long) until one has or one closes;
//   - pipelined requests are answered in order, one at a time (the next is read when the
//     previous response has gone);
//   - stop() gives the browsers stop_flush to take what is queued for them, then closes every
//     connection: it never waits on a client longer than that.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "drivers/net/host_port.h"
#include "drivers/net/http_request.h"
#include "web/web_hub.h"

namespace sonarloop::web {

struct WebServerOptions {
  std::size_t max_head_bytes = net::kDefaultMaxHttpHeadBytes;
  std::chrono::milliseconds request_timeout{5000};
  std::chrono::milliseconds write_timeout{5000};
  int max_connections = 32;
  std::chrono::milliseconds stop_flush{250};
};

struct WebServerCounters {
  std::uint64_t connections = 0;   // accepted
  std::uint64_t evicted = 0;       // closed, still waiting for a request, to make room
  std::uint64_t requests = 0;      // whole request heads answered
  std::uint64_t bad_requests = 0;  // 400, 405, 413, 431, 505
  std::uint64_t timeouts = 0;      // a request begun, not whole in time (408); a stalled write
};

class WebServer {
 public:
  // Binds `address` ("localhost" is 127.0.0.1; port 0: a free port) and starts serving.
  // Throws std::runtime_error naming the address when it cannot bind (port in use), or
  // std::invalid_argument for bad options.
  WebServer(WebHub& hub, const net::HostPort& address, const WebServerOptions& options = {});
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  // The address served, with the port bound.
  const net::HostPort& address() const;
  // "http://127.0.0.1:8080/" (IPv6 in brackets).
  std::string url() const;
  WebServerCounters counters() const;
  // Ends every stream (after up to stop_flush of sending what is queued) and the server's
  // thread. Idempotent; the destructor calls it.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sonarloop::web
