#pragma once
// What the socketcand server's tests share (socketcand_server_test.cpp: the protocol and the
// readers; socketcand_server_faults_test.cpp: the faults of the outside world): a polling wait,
// the frame pattern python_socketcand_peer.py also uses, a bare TCP client for byte-exact checks,
// a warning log, and pattern senders and readers.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "drivers/can/socketcand_client.h"
#include "drivers/can/socketcand_server.h"

namespace sonarloop::can::socketcand_test {

using sonarloop::net::HostPort;

inline const HostPort kLoopbackAnyPort{"127.0.0.1", 0};

// Polls `done` every 5 ms for up to 30 s (a bound against hangs, not a timing assertion).
inline bool wait_until(const std::function<bool()>& done) {
  for (int i = 0; i < 6000; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

// The frame pattern shared with python_socketcand_peer.py.
inline TimedCanFrame pattern(int i) {
  TimedCanFrame t;
  t.frame.id = (0x09F80100u + static_cast<std::uint32_t>(i)) & kCanEffMask;
  t.frame.extended = true;
  t.frame.len = static_cast<std::uint8_t>(i % 9);
  for (int k = 0; k < t.frame.len; ++k)
    t.frame.data[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>((i * 7 + k) & 0xFF);
  t.t_ns = 1'700'000'000'000'000'000 + static_cast<std::int64_t>(i) * 1'000'000;
  return t;
}

// A bare TCP client for byte-exact protocol checks.
class RawClient {
 public:
  explicit RawClient(std::uint16_t port, int rcvbuf = 0) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    if (rcvbuf > 0) ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0)
      throw std::runtime_error("connect failed");
  }
  ~RawClient() {
    if (fd_ >= 0) ::close(fd_);
  }
  // Closes at once; with `reset`, by a TCP RST that discards whatever is unread (SO_LINGER 0),
  // as a crashed or killed client would.
  void close_now(bool reset) {
    if (reset) {
      const linger hard{1, 0};
      ::setsockopt(fd_, SOL_SOCKET, SO_LINGER, &hard, sizeof hard);
    }
    ::close(fd_);
    fd_ = -1;
  }
  void put(const std::string& s) { REQUIRE(::send(fd_, s.data(), s.size(), MSG_NOSIGNAL) > 0); }
  // What arrives in one recv() within 5 s ("" on timeout or close).
  std::string get() {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, 5000) <= 0) return "";
    char buf[4096];
    const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
    return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : std::string();
  }
  // Everything the server sent, up to its close (at most 30 s).
  std::string read_to_eof() {
    std::string all;
    char buf[65536];
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < until) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 100) <= 0) continue;
      const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) break;
      all.append(buf, static_cast<std::size_t>(n));
    }
    return all;
  }
  // True when the server closes the connection within `ms` (anything it sends first is skipped).
  bool closed_within(int ms) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
    char buf[4096];
    while (std::chrono::steady_clock::now() < until) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 50) <= 0) continue;
      if (::recv(fd_, buf, sizeof buf, 0) <= 0) return true;
    }
    return false;
  }
  void handshake() {
    REQUIRE(get() == "< hi >");
    put("< open vcan0 >");
    REQUIRE(get() == "< ok >");
    put("< rawmode >");
    REQUIRE(get() == "< ok >");
  }

 private:
  int fd_ = -1;
};

// Collects the server's warnings (from its I/O thread or a send() caller).
struct WarningLog {
  std::mutex mu;
  std::vector<std::string> lines;
  std::function<void(const std::string&)> sink() {
    return [this](const std::string& w) {
      std::lock_guard lock(mu);
      lines.push_back(w);
    };
  }
  std::size_t count_containing(const std::string& text) {
    std::lock_guard lock(mu);
    return static_cast<std::size_t>(
        std::count_if(lines.begin(), lines.end(),
                      [&](const std::string& l) { return l.find(text) != std::string::npos; }));
  }
};

// Reads `frames` frames from `client`; returns how many matched pattern(0..) in order, and
// keeps `progress` (if given) at that count while reading.
inline int read_pattern(SocketcandClient& client, int frames,
                        std::atomic<int>* progress = nullptr) {
  for (int i = 0; i < frames; ++i) {
    const auto got = client.receive_timed(10000);
    const TimedCanFrame want = pattern(i);
    if (!got || !(got->frame == want.frame) || got->t_ns != want.t_ns) return i;
    if (progress) *progress = i + 1;
  }
  return frames;
}

inline void send_pattern(SocketcandServer& server, int first, int last) {
  for (int i = first; i < last; ++i) {
    const TimedCanFrame f = pattern(i);
    server.send(f.frame, f.t_ns);
  }
}

}  // namespace sonarloop::can::socketcand_test
