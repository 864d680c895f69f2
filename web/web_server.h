#pragma once
// The live operator view's HTTP server (docs/web.md): cpp-httplib on threads of its own, serving
//   GET /            the page (web/web_page.h): HTML, script and style inline, nothing
//                    fetched from elsewhere
//   GET /events      the hub's events as Server-Sent Events (text/event-stream), pushed as
//                    they come; a comment line every second keeps an idle stream alive and
//                    finds a vanished browser; at most WebHubOptions::max_clients at once (503)
//   GET /stats.json  the latest statistics with the hub's counters
// and nothing else: every other path or method gets 404. Read-only: nothing a browser sends
// changes the run. A browser that stops reading blocks only its own connection's thread (write
// timeout 5 s); its queue in the hub drops its oldest events.
//
// Built without cpp-httplib (Debian libcpp-httplib-dev), the constructor throws
// WebUnavailable, and web_available() is false.
#include <memory>
#include <stdexcept>
#include <string>

#include "drivers/net/host_port.h"
#include "web/web_hub.h"

namespace sonarloop::web {

struct WebUnavailable : std::runtime_error {
  WebUnavailable()
      : std::runtime_error(
            "this sonarloop was built without web support (cpp-httplib was not found: install "
            "libcpp-httplib-dev and rebuild)") {}
};

// Whether this build can serve the page.
bool web_available();

class WebServer {
 public:
  // Binds `address` ("localhost" is 127.0.0.1; port 0: a free port) and starts serving.
  // Throws std::runtime_error naming the address when it cannot bind (port in use), or
  // WebUnavailable.
  WebServer(WebHub& hub, const net::HostPort& address);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  // The address served, with the port bound.
  const net::HostPort& address() const;
  // "http://127.0.0.1:8080/" (IPv6 in brackets).
  std::string url() const;
  // Ends every stream and the server's threads. Idempotent; the destructor calls it.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sonarloop::web
