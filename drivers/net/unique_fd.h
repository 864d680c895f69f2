#pragma once
// A file descriptor owned by one object and closed when it goes out of scope (move-only), and
// errno as text. Shared by the UDP, TCP and CAN transports.
#include <cerrno>
#include <string>
#include <system_error>
#include <utility>

#include <unistd.h>

namespace sonarloop::net {

class UniqueFd {
 public:
  UniqueFd() = default;
  explicit UniqueFd(int fd) : fd_(fd) {}
  ~UniqueFd() { reset(); }
  UniqueFd(UniqueFd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  UniqueFd& operator=(UniqueFd&& other) noexcept {
    if (this != &other) {
      reset();
      fd_ = std::exchange(other.fd_, -1);
    }
    return *this;
  }
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;

  int get() const { return fd_; }
  bool valid() const { return fd_ >= 0; }
  // Gives up ownership without closing.
  int release() { return std::exchange(fd_, -1); }
  void reset(int fd = -1) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = fd;
  }

 private:
  int fd_ = -1;
};

// "Address already in use" for an errno value (thread-safe, unlike strerror). A full disk says
// so in words a user recognises: "No space left on device (ENOSPC: the disk is full)".
inline std::string errno_text(int err) {
  std::string text = std::error_code(err, std::generic_category()).message();
  if (err == ENOSPC) text += " (ENOSPC: the disk is full)";
  if (err == EDQUOT) text += " (EDQUOT: the disk quota is used up)";
  return text;
}

}  // namespace sonarloop::net
