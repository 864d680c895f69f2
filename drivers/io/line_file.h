#pragma once
// A text file written one whole record (line) at a time: each append() is one pwrite(2) at the
// end of the records written so far, so a crash (even SIGKILL) or a full disk never leaves a
// record torn mid-line. A failed or short write is cut back with ftruncate(2) to the last whole
// record and reported; the file then stays as it was (whole records only) and further appends
// are refused with the same error.
//
// Used by the recordings whose readers parse lines (`run --record`'s nav.log and truth.csv,
// `--can log:FILE`). There is no user-space buffer: one system call per record, which costs
// about a microsecond, far below the rates at which these files grow.
//
// Errors name the file and say, in words, why: "No space left on device (ENOSPC: the disk is
// full)" for a full disk (net::errno_text).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace sonarloop::io {

// Writes `size` bytes at byte `offset` of the file `fd` (pwrite, retried after a short write or
// EINTR). On failure it cuts the file back to `offset` (ftruncate; a device such as /dev/full
// cannot be cut and has nothing to cut) and returns the errno value; 0 on success. The unit of
// whole records that LineFile and xtf::XtfWriter build on.
int append_whole(int fd, std::uint64_t offset, const void* data, std::size_t size);

class LineFile {
 public:
  // Creates or truncates `path`. Throws std::runtime_error "`what` PATH: cannot create: ..."
  // (`what` names the file's role, e.g. "candump log").
  LineFile(const std::string& path, std::string what);
  ~LineFile();
  LineFile(const LineFile&) = delete;
  LineFile& operator=(const LineFile&) = delete;

  // Appends one record (normally a line ending in '\n') with one write. Throws
  // std::runtime_error naming the file, the byte offset and the reason on failure (the file is
  // cut back to its previous whole records), and on every later call. Allocation-free unless it
  // throws.
  void append(std::string_view record);
  // Closes the file (idempotent). Throws std::runtime_error if closing fails.
  void close();

  const std::string& path() const { return path_; }
  std::uint64_t bytes_written() const { return bytes_written_; }
  // The first write error ("" if none).
  const std::string& error() const { return error_; }

 private:
  std::string path_;
  std::string what_;
  int fd_ = -1;
  std::uint64_t bytes_written_ = 0;
  std::string error_;
};

}  // namespace sonarloop::io
