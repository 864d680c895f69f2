// The only source file that includes cpp-httplib (a heavy header): see web_server.h.
#include "web/web_server.h"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include <sys/socket.h>

#include "web/web_page.h"

#ifdef SONARLOOP_HAVE_HTTPLIB
#include <httplib.h>
#endif

namespace sonarloop::web {

std::string WebServer::url() const {
  const net::HostPort& a = address();
  const bool v6 = a.host.find(':') != std::string::npos;
  return "http://" + (v6 ? "[" + a.host + "]" : a.host) + ":" + std::to_string(a.port) + "/";
}

#ifndef SONARLOOP_HAVE_HTTPLIB

bool web_available() {
  return false;
}

struct WebServer::Impl {
  net::HostPort bound;
};

WebServer::WebServer(WebHub&, const net::HostPort&) {
  throw WebUnavailable();
}
WebServer::~WebServer() = default;
const net::HostPort& WebServer::address() const {
  return impl_->bound;
}
void WebServer::stop() {}

#else

namespace {

// A quiet stream sends a comment line this often: it keeps proxies and the browser from timing
// out, and a write to a vanished browser fails, which ends its stream.
constexpr std::chrono::milliseconds kIdleCommentEvery{1000};
// Seconds a browser may stall a write before its connection is dropped.
constexpr time_t kWriteTimeoutS = 5;
// Seconds an idle keep-alive connection holds one of the server's threads.
constexpr time_t kKeepAliveS = 2;
// Milliseconds the constructor waits for the server's thread to start listening.
constexpr int kStartPolls = 5000;

}  // namespace

bool web_available() {
  return true;
}

struct WebServer::Impl {
  Impl(WebHub& h) : hub(h) {}

  void serve_events(httplib::Response& res);
  void forget(const std::shared_ptr<WebClient>& client) {
    hub.unsubscribe(client);
    std::lock_guard lock(mutex);
    streams.erase(std::remove(streams.begin(), streams.end(), client), streams.end());
  }

  WebHub& hub;
  httplib::Server server;
  net::HostPort bound;
  std::thread thread;
  std::mutex mutex;
  std::vector<std::shared_ptr<WebClient>> streams;  // open /events connections
  bool stopped = false;
};

void WebServer::Impl::serve_events(httplib::Response& res) {
  std::shared_ptr<WebClient> client = hub.subscribe();
  if (client) {
    std::lock_guard lock(mutex);
    if (stopped) {
      client->close();
    } else {
      streams.push_back(client);
    }
  }
  if (!client) {
    res.status = 503;
    res.set_content("too many viewers of this run; close another page and reload\n",
                    "text/plain; charset=utf-8");
    return;
  }
  res.set_chunked_content_provider(
      "text/event-stream",
      [client](std::size_t, httplib::DataSink& sink) {
        Event e;
        switch (client->next(e, kIdleCommentEvery)) {
          case WebClient::Next::kEvent:
            return sink.write(e->data(), e->size());
          case WebClient::Next::kTimeout:
            return sink.write(": idle\n\n", 8);
          case WebClient::Next::kClosed:
            break;
        }
        sink.done();
        return true;
      },
      [this, client](bool) { forget(client); });
}

WebServer::WebServer(WebHub& hub, const net::HostPort& address)
    : impl_(std::make_unique<Impl>(hub)) {
  httplib::Server& s = impl_->server;
  s.set_default_headers({{"Cache-Control", "no-store"},
                         {"X-Content-Type-Options", "nosniff"},
                         {"Content-Security-Policy",
                          "default-src 'none'; script-src 'unsafe-inline'; style-src "
                          "'unsafe-inline'; connect-src 'self'; img-src 'self' data:"}});
  s.set_write_timeout(kWriteTimeoutS, 0);
  s.set_keep_alive_timeout(kKeepAliveS);
  s.set_payload_max_length(0);  // no request bodies
  // SO_REUSEADDR only: cpp-httplib's default adds SO_REUSEPORT, which would let a second run
  // share the port silently instead of failing
  s.set_socket_options([](socket_t sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  s.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(kWebPage, "text/html; charset=utf-8");
  });
  s.Get("/stats.json", [this](const httplib::Request&, httplib::Response& res) {
    res.set_content(impl_->hub.stats_json() + "\n", "application/json");
  });
  s.Get("/events",
        [this](const httplib::Request&, httplib::Response& res) { impl_->serve_events(res); });
  s.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (res.body.empty()) {
      res.set_content(std::to_string(res.status) + ": not served here (GET / for the page)\n",
                      "text/plain; charset=utf-8");
    }
  });

  // no name lookups: "localhost" is the loopback address (drivers/net/host_port.h)
  const std::string host = address.host == "localhost" ? "127.0.0.1" : address.host;
  impl_->bound = {host, address.port};
  int port = address.port;
  const bool ok = port == 0 ? (port = s.bind_to_any_port(host)) > 0 : s.bind_to_port(host, port);
  if (!ok) {
    throw std::runtime_error("--web: cannot listen on " + net::to_string(address) +
                             " (port in use, or not an address of this machine)");
  }
  impl_->bound.port = static_cast<std::uint16_t>(port);
  impl_->thread = std::thread([this] { impl_->server.listen_after_bind(); });
  // stop() only stops a server that runs: wait for the thread to get there
  for (int i = 0; i < kStartPolls && !impl_->server.is_running(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

WebServer::~WebServer() {
  stop();
}

const net::HostPort& WebServer::address() const {
  return impl_->bound;
}

void WebServer::stop() {
  std::vector<std::shared_ptr<WebClient>> streams;
  {
    std::lock_guard lock(impl_->mutex);
    if (impl_->stopped) return;
    impl_->stopped = true;
    streams = impl_->streams;
  }
  // each stream's provider sees kClosed and ends its response; then the server's threads end
  for (auto& c : streams)
    c->close();
  impl_->server.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
}

#endif

}  // namespace sonarloop::web
