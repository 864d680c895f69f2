#include "drivers/io/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <stdexcept>

#include "drivers/net/unique_fd.h"

namespace sonarloop::io {
namespace {

std::string bytes_text(std::uint64_t b) {
  char s[32];
  if (b >= 1'000'000'000) {
    std::snprintf(s, sizeof s, "%.1f GB", static_cast<double>(b) * 1e-9);
  } else if (b >= 1'000'000) {
    std::snprintf(s, sizeof s, "%.1f MB", static_cast<double>(b) * 1e-6);
  } else {
    std::snprintf(s, sizeof s, "%llu bytes", static_cast<unsigned long long>(b));
  }
  return s;
}

}  // namespace

std::string file_type_name(unsigned mode) {
  switch (mode & S_IFMT) {
    case S_IFREG:
      return "a regular file";
    case S_IFDIR:
      return "a directory";
    case S_IFIFO:
      return "a FIFO";
    case S_IFCHR:
      return "a character device";
    case S_IFBLK:
      return "a block device";
    case S_IFSOCK:
      return "a socket";
    case S_IFLNK:
      return "a symbolic link";
    default:
      return "not a file";
  }
}

std::uint64_t check_input_file(const std::string& path, std::string_view what,
                               std::uint64_t max_bytes) {
  const std::string name = std::string(what) + " '" + path + "'";
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    throw std::runtime_error(name + ": cannot open: " + net::errno_text(errno));
  }
  if (!S_ISREG(st.st_mode)) {
    throw std::runtime_error(name + ": not a regular file (" + file_type_name(st.st_mode) + ")");
  }
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > max_bytes) {
    throw std::runtime_error(name + ": " + bytes_text(size) + ", more than the " +
                             bytes_text(max_bytes) + " a " + std::string(what) + " may be");
  }
  return size;
}

}  // namespace sonarloop::io
