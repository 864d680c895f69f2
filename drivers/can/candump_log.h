#pragma once
// candump log files (docs/formats.md §3): the line format of can-utils `candump -l`, read by
// can-utils (log2asc, canplayer), canboat and python-can's CanutilsLogReader.
//
// Writer: one line per frame, no header or comments (python-can rejects them):
//   (1699999999.123456) vcan0 09F80123#00E6B523B1AC6A06
// i.e. "(%010llu.%06llu) CHANNEL %08X#DATA\n" (%03X for 11-bit ids), uppercase hex, the EFF id
// without flag bits, time truncated to microseconds. Lines are buffered (64 KiB) and written on
// flush(), when the buffer fills, and on close/destruction.
//
// Reader: the lines of can-utils and python-can writers: "(SEC.FRAC) CHANNEL FRAME[ R|T]" with
// FRAME = ID#DATA (ID 3 hex digits SFF or 8 EFF, DATA 0..8 bytes as hex pairs, optional '.'
// between bytes, optional _L len8_dlc suffix), ID#R[LEN] (remote), ID##FDATA (CAN FD, F = flags
// digit) and error frames (CAN_ERR_FLAG in an 8-digit id). Blank lines and lines starting with
// '#' are skipped. A malformed line is an error naming the file, the line number and what is
// wrong.
#include <array>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "drivers/can/can_transport.h"
#include "drivers/io/line_file.h"

namespace sonarloop::can {

// Writes a candump log; also a CanTransport (`--can log:FILE`). Thread-safe.
class CandumpLogWriter final : public CanTransport {
 public:
  // Creates or truncates `path`. Throws std::runtime_error naming the file.
  explicit CandumpLogWriter(const std::string& path, std::string channel = "vcan0");
  ~CandumpLogWriter() override;  // flushes and closes; errors there are printed to stderr
  CandumpLogWriter(const CandumpLogWriter&) = delete;
  CandumpLogWriter& operator=(const CandumpLogWriter&) = delete;

  // Appends one line with one write (io::LineFile: a crash or a full disk never leaves a torn
  // line). t_ns >= 0 (ns since the UNIX epoch); throws std::invalid_argument for a negative
  // time and std::runtime_error on a write error (naming the file and saying "the disk is full"
  // for ENOSPC) or after close(). Allocation-free unless it throws.
  void write(const CanFrame& frame, std::int64_t t_ns);
  void send(const CanFrame& frame, std::int64_t t_ns) override { write(frame, t_ns); }
  std::string describe() const override { return "candump log " + path_; }
  // Nothing to do: every line is written when it is sent.
  void flush() override;
  // Flushes and closes; later writes throw. Throws std::runtime_error on an I/O error.
  void close();

  std::uint64_t frames_written() const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::string channel_;
  mutable std::mutex mu_;
  std::unique_ptr<io::LineFile> file_;
  std::uint64_t frames_ = 0;
};

// Formats one log line (with the trailing '\n') into `out`; returns its length (0 if `out` is too
// small: 64 + channel length bytes always suffice). t_ns must be >= 0.
std::size_t format_candump_line(const CanFrame& frame, std::int64_t t_ns, std::string_view channel,
                                char* out, std::size_t out_size);

enum class CandumpFrameKind : std::uint8_t { kData, kRemote, kError, kFd };

struct CandumpRecord {
  std::int64_t t_ns = 0;  // timestamp (ns; the log's epoch, usually UNIX time)
  std::string channel;    // "vcan0"
  CandumpFrameKind kind = CandumpFrameKind::kData;
  CanFrame frame;             // data, remote and error frames: id, extended, len (remote: the
                              // requested length, data zero)
  std::uint8_t len8_dlc = 0;  // raw DLC 9..15 of an 8-byte classic frame ("_L" suffix), else 0
  std::uint8_t fd_flags = 0;  // FD only: flags digit (1 BRS, 2 ESI, 4 FDF)
  std::uint8_t fd_len = 0;    // FD only: payload length (0..8, 12, 16, 20, 24, 32, 48, 64)
  std::array<std::uint8_t, 64> fd_data{};  // FD only: payload
  char direction = 0;                      // 'R' or 'T' when the line has the marker, else 0
};

enum class CandumpLineStatus : std::uint8_t { kRecord, kSkip, kError };

// Parses one line (a trailing "\n" or "\r\n" is allowed). kRecord fills `out`; kSkip for blank
// and '#' lines; kError sets `error` to what is wrong (without file or line number).
CandumpLineStatus parse_candump_line(std::string_view line, CandumpRecord& out, std::string& error);

// Reads a candump log record by record.
class CandumpReader {
 public:
  // strict: a malformed line throws std::runtime_error "FILE:LINE: what: 'text'". Otherwise it is
  // skipped and counted (malformed_lines(), last_error()). Throws if the file cannot be opened.
  // ignore_torn_tail: a last line without its '\n' (a write torn by a crash or a full disk;
  // every candump writer ends its lines) is not read, not even when it parses, and torn_tail()
  // gives its line number; otherwise it is read as any line.
  explicit CandumpReader(const std::string& path, bool strict = true,
                         bool ignore_torn_tail = false);

  // The next record, nullopt at the end of the file.
  std::optional<CandumpRecord> next();

  std::size_t line_number() const { return line_number_; }  // of the last line read
  std::size_t malformed_lines() const { return malformed_; }
  const std::string& last_error() const { return last_error_; }
  // Line number of the torn last line that was ignored (0: none, or not at the end yet).
  std::size_t torn_tail() const { return torn_tail_; }

 private:
  std::string path_;
  bool strict_;
  bool ignore_torn_tail_;
  std::size_t torn_tail_ = 0;
  std::ifstream in_;
  std::string line_;
  std::size_t line_number_ = 0;
  std::size_t malformed_ = 0;
  std::string last_error_;
};

}  // namespace sonarloop::can
