#include "drivers/io/line_file.h"

#include <cerrno>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

#include "drivers/net/unique_fd.h"

namespace sonarloop::io {

int append_whole(int fd, std::uint64_t offset, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const char*>(data);
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::pwrite(fd, bytes + done, size - done, static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : EIO;
      if (done > 0 && ::ftruncate(fd, static_cast<off_t>(offset)) != 0) {
        // the write error is the one reported
      }
      return err;
    }
    done += static_cast<std::size_t>(n);
  }
  return 0;
}

LineFile::LineFile(const std::string& path, std::string what)
    : path_(path), what_(std::move(what)) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::runtime_error(what_ + " " + path_ + ": cannot create: " + net::errno_text(errno));
  }
}

LineFile::~LineFile() {
  if (fd_ >= 0) ::close(fd_);
}

void LineFile::append(std::string_view record) {
  if (!error_.empty()) throw std::runtime_error(error_);
  if (fd_ < 0) throw std::runtime_error(what_ + " " + path_ + ": write after close");
  if (const int err = append_whole(fd_, bytes_written_, record.data(), record.size())) {
    error_ = what_ + " " + path_ + ": write of " + std::to_string(record.size()) +
             " bytes at byte offset " + std::to_string(bytes_written_) +
             " failed: " + net::errno_text(err) + "; the file keeps the " +
             std::to_string(bytes_written_) + " bytes of whole lines written before";
    throw std::runtime_error(error_);
  }
  bytes_written_ += record.size();
}

void LineFile::close() {
  if (fd_ < 0) return;
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    throw std::runtime_error(what_ + " " + path_ + ": closing failed: " + net::errno_text(errno));
  }
}

}  // namespace sonarloop::io
