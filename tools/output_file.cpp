#include "tools/output_file.h"

#include <cerrno>
#include <stdexcept>

#include "drivers/net/unique_fd.h"

namespace sonarloop::tools {

OutputFile::OutputFile(std::string option, std::string path)
    : option_(std::move(option)),
      path_(std::move(path)),
      file_(std::fopen(path_.c_str(), "w"), &std::fclose) {
  if (!file_) {
    throw std::runtime_error(option_ + " " + path_ + ": cannot write: " + net::errno_text(errno));
  }
}

void OutputFile::write_and_close(const std::string& text) {
  errno = 0;
  const bool written = std::fwrite(text.data(), 1, text.size(), file_.get()) == text.size();
  int err = errno;
  // fclose flushes: a full disk shows here
  const bool closed = std::fclose(file_.release()) == 0;
  if (!closed && err == 0) err = errno;
  if (!written || !closed) {
    throw std::runtime_error(option_ + " " + path_ +
                             ": cannot write: " + net::errno_text(err != 0 ? err : EIO));
  }
}

void make_folder(const std::string& option, const std::filesystem::path& dir) {
  std::error_code ec;
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  if (ec) {
    throw std::runtime_error(option + " " + dir.string() + ": cannot make it: " + ec.message());
  }
}

}  // namespace sonarloop::tools
