#pragma once
// Clients of a `--web` server that a careful attacker or an unlucky network would be (issue 29),
// for the command-line tests of `run --web` and `onboard --web`: on threads of their own until
// stop(), each reconnecting when the server closes it,
//   - slow: the request line, then one header byte every 100 ms (slowloris);
//   - headers: an endless header block, as fast as the server takes it;
//   - line: an endless request line.
// Loopback only. Counts the connections made and the answers seen (408, 431).
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

namespace sonarloop::testing {

class HostileWebClients {
 public:
  explicit HostileWebClients(std::uint16_t port, int slow_clients = 4) : port_(port) {
    for (int i = 0; i < slow_clients; ++i)
      threads_.emplace_back([this] { attack("GET / HTTP/1.1\r\n", "X", 100); });
    threads_.emplace_back([this] {
      std::string block;
      for (int i = 0; i < 512; ++i)
        block += "X-a: b\r\n";
      attack("GET / HTTP/1.1\r\nHost: a\r\n", block, 0);
    });
    threads_.emplace_back([this] { attack("GET /", std::string(4096, 'a'), 0); });
  }
  ~HostileWebClients() { stop(); }
  HostileWebClients(const HostileWebClients&) = delete;
  HostileWebClients& operator=(const HostileWebClients&) = delete;

  void stop() {
    stop_ = true;
    for (auto& t : threads_)
      if (t.joinable()) t.join();
  }
  int connections() const { return connections_; }
  int timeouts_seen() const { return timeouts_seen_; }    // 408 answers
  int too_large_seen() const { return too_large_seen_; }  // 431 answers

 private:
  // Connects, sends `start`, then `repeat` every `every_ms` (0: as fast as it goes) until the
  // server answers or closes; then again, until stop().
  void attack(const std::string& start, const std::string& repeat, int every_ms) {
    while (!stop_) {
      const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
      if (fd < 0) return;
      sockaddr_in a{};
      a.sin_family = AF_INET;
      a.sin_port = htons(port_);
      a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
        ::close(fd);
        std::this_thread::sleep_for(std::chrono::milliseconds(50));  // the server has gone
        continue;
      }
      ++connections_;
      bool open = ::send(fd, start.data(), start.size(), MSG_NOSIGNAL) > 0;
      while (open && !stop_) {
        pollfd p{fd, static_cast<short>(POLLIN | (every_ms == 0 ? POLLOUT : 0)), 0};
        const int r = ::poll(&p, 1, every_ms == 0 ? 100 : every_ms);
        if (r > 0 && (p.revents & (POLLIN | POLLERR | POLLHUP))) break;
        if (r < 0) break;
        open = ::send(fd, repeat.data(), repeat.size(), MSG_NOSIGNAL | MSG_DONTWAIT) > 0 ||
               errno == EAGAIN;
      }
      char answer[32] = {};
      if (::recv(fd, answer, sizeof answer - 1, MSG_DONTWAIT) > 0) {
        const std::string got(answer);
        if (got.rfind("HTTP/1.1 408", 0) == 0) ++timeouts_seen_;
        if (got.rfind("HTTP/1.1 431", 0) == 0) ++too_large_seen_;
      }
      ::close(fd);
    }
  }

  const std::uint16_t port_;
  std::atomic<bool> stop_{false};
  std::atomic<int> connections_{0}, timeouts_seen_{0}, too_large_seen_{0};
  std::vector<std::thread> threads_;
};

}  // namespace sonarloop::testing
