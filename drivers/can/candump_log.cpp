#include "drivers/can/candump_log.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <stdexcept>

#include "drivers/can/can_text.h"
#include "drivers/io/input_file.h"
#include "drivers/io/line_file.h"
#include "drivers/net/unique_fd.h"

namespace sonarloop::can {
namespace {

constexpr std::uint32_t kCanErrFlag = 0x20000000u;  // linux/can.h CAN_ERR_FLAG
constexpr std::size_t kMaxChannelChars = 64;

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

// Longest piece of input quoted in a message.
constexpr std::size_t kMaxQuotedChars = 100;

std::string quoted(std::string_view s) {
  // built by appending: GCC 12's -Wrestrict misfires on "'" + std::string(s) + "'" at -O3.
  // Input in messages is cut to kMaxQuotedChars: a 10 MB line must not be echoed whole.
  std::string out;
  const bool cut = s.size() > kMaxQuotedChars;
  out.reserve(std::min(s.size(), kMaxQuotedChars) + 40);
  out += '\'';
  out += s.substr(0, kMaxQuotedChars);
  if (cut) {
    out += "...' (";
    out += std::to_string(s.size());
    out += " characters)";
  } else {
    out += '\'';
  }
  return out;
}

// "(SEC.FRAC)" -> ns. FRAC has 0..9 digits (candump writes 6, candump -N 9).
bool parse_timestamp(std::string_view tok, std::int64_t& t_ns, std::string& error) {
  if (tok.size() < 3 || tok.front() != '(' || tok.back() != ')') {
    error = "timestamp " + quoted(tok) + " is not '(SECONDS.FRACTION)'";
    return false;
  }
  const std::string_view inner = tok.substr(1, tok.size() - 2);
  const auto dot = inner.find('.');
  const std::string_view sec = inner.substr(0, dot);
  const std::string_view frac = dot == std::string_view::npos ? "" : inner.substr(dot + 1);
  std::uint64_t s = 0;
  const auto [end, ec] = std::from_chars(sec.data(), sec.data() + sec.size(), s);
  if (sec.empty() || ec != std::errc() || end != sec.data() + sec.size()) {
    error = "timestamp " + quoted(tok) + " has no valid seconds";
    return false;
  }
  if (s > 9'000'000'000ull) {
    error = "timestamp " + quoted(tok) + " is out of range";
    return false;
  }
  if (frac.size() > 9) {
    error = "timestamp " + quoted(tok) + " has more than 9 fraction digits";
    return false;
  }
  std::int64_t ns = 0;
  for (std::size_t i = 0; i < 9; ++i) {
    int digit = 0;
    if (i < frac.size()) {
      if (frac[i] < '0' || frac[i] > '9') {
        error = "timestamp " + quoted(tok) + " has a non-digit in its fraction";
        return false;
      }
      digit = frac[i] - '0';
    }
    ns = ns * 10 + digit;
  }
  t_ns = static_cast<std::int64_t>(s) * kNsPerSecond + ns;
  return true;
}

// Hex bytes "0011AA" or "00.11.AA" into out (at most max_bytes); stops at '_' or the end.
// Returns the number of characters consumed, or npos with `error` set.
std::size_t parse_hex_bytes(std::string_view s, std::uint8_t* out, std::size_t max_bytes,
                            std::size_t& count, std::string& error) {
  std::size_t i = 0;
  count = 0;
  while (i < s.size() && s[i] != '_') {
    if (s[i] == '.' && count > 0 && i + 1 < s.size() && s[i + 1] != '.') {
      ++i;
      continue;
    }
    if (i + 1 >= s.size() || hex_value(s[i]) < 0 || hex_value(s[i + 1]) < 0) {
      error = "data " + quoted(s) + " is not a sequence of 2-digit hex bytes";
      return std::string_view::npos;
    }
    if (count == max_bytes) {
      error = "data " + quoted(s) + " has more than " + std::to_string(max_bytes) + " bytes";
      return std::string_view::npos;
    }
    out[count++] = static_cast<std::uint8_t>(hex_value(s[i]) * 16 + hex_value(s[i + 1]));
    i += 2;
  }
  return i;
}

bool valid_fd_length(std::size_t n) {
  return n <= 8 || n == 12 || n == 16 || n == 20 || n == 24 || n == 32 || n == 48 || n == 64;
}

bool parse_frame(std::string_view tok, CandumpRecord& out, std::string& error) {
  const auto hash = tok.find('#');
  if (hash == std::string_view::npos) {
    error = "frame " + quoted(tok) + " has no '#' between id and data";
    return false;
  }
  const std::string_view id_text = tok.substr(0, hash);
  std::uint32_t id = 0;
  for (char c : id_text) {
    const int v = hex_value(c);
    if (v < 0) {
      error = "CAN id " + quoted(id_text) + " is not hexadecimal";
      return false;
    }
    id = id * 16 + static_cast<std::uint32_t>(v);
  }
  CanFrame& f = out.frame;
  f = CanFrame{};
  out.kind = CandumpFrameKind::kData;
  if (id_text.size() == 3) {
    if (id > kCanSffMask) {
      error = "11-bit CAN id " + quoted(id_text) + " is larger than 7FF";
      return false;
    }
    f.extended = false;
    f.id = id;
  } else if (id_text.size() == 8) {
    if (id & kCanErrFlag) {
      out.kind = CandumpFrameKind::kError;
      f.extended = false;
      f.id = id & kCanEffMask;
    } else if (id > kCanEffMask) {
      error = "29-bit CAN id " + quoted(id_text) + " has flag bits above bit 28";
      return false;
    } else {
      f.extended = true;
      f.id = id;
    }
  } else {
    error = "CAN id " + quoted(id_text) + " must have 3 (11-bit) or 8 (29-bit) hex digits";
    return false;
  }

  std::string_view rest = tok.substr(hash + 1);
  if (!rest.empty() && rest.front() == '#') {  // CAN FD: ##<flags><data>
    if (rest.size() < 2 || hex_value(rest[1]) < 0) {
      error = "CAN FD frame " + quoted(tok) + " needs a flags digit after '##'";
      return false;
    }
    out.kind = CandumpFrameKind::kFd;
    out.fd_flags = static_cast<std::uint8_t>(hex_value(rest[1]));
    std::size_t count = 0;
    const std::string_view data = rest.substr(2);
    const std::size_t used = parse_hex_bytes(data, out.fd_data.data(), 64, count, error);
    if (used == std::string_view::npos) return false;
    if (used != data.size()) {
      error = "CAN FD data " + quoted(data) + " has trailing characters";
      return false;
    }
    if (!valid_fd_length(count)) {
      error = "CAN FD payload of " + std::to_string(count) +
              " bytes is not a valid FD length (0..8, 12, 16, 20, 24, 32, 48, 64)";
      return false;
    }
    out.fd_len = static_cast<std::uint8_t>(count);
    return true;
  }
  if (!rest.empty() && (rest.front() == 'R' || rest.front() == 'r')) {  // remote: R[len][_dlc]
    out.kind = CandumpFrameKind::kRemote;
    rest.remove_prefix(1);
    if (!rest.empty() && rest.front() >= '0' && rest.front() <= '9') {
      f.len = static_cast<std::uint8_t>(rest.front() - '0');
      if (f.len > 8) {
        error = "remote frame length " + std::string(1, rest.front()) + " is larger than 8";
        return false;
      }
      rest.remove_prefix(1);
    }
  } else {
    std::size_t count = 0;
    const std::size_t used = parse_hex_bytes(rest, f.data.data(), 8, count, error);
    if (used == std::string_view::npos) return false;
    f.len = static_cast<std::uint8_t>(count);
    rest.remove_prefix(used);
  }
  if (!rest.empty()) {  // _<len8_dlc>: raw DLC 9..F of an 8-byte classic frame
    const int dlc = rest.size() == 2 && rest[0] == '_' ? hex_value(rest[1]) : -1;
    if (dlc < 9 || f.len != 8) {
      error = "frame " + quoted(tok) + " has trailing characters " + quoted(rest) +
              " (only _9.._F after 8 data bytes is allowed)";
      return false;
    }
    out.len8_dlc = static_cast<std::uint8_t>(dlc);
  }
  return true;
}

}  // namespace

std::size_t format_candump_line(const CanFrame& frame, std::int64_t t_ns, std::string_view channel,
                                char* out, std::size_t out_size) {
  const std::uint8_t len = frame.len > 8 ? 8 : frame.len;
  const std::size_t needed = 40 + channel.size() + 2 * len;
  if (out_size < needed || t_ns < 0) return 0;
  const auto sec = static_cast<unsigned long long>(t_ns / kNsPerSecond);
  const auto usec = static_cast<unsigned long long>((t_ns % kNsPerSecond) / 1000);
  int n = std::snprintf(out, out_size, "(%010llu.%06llu) %.*s ", sec, usec,
                        static_cast<int>(channel.size()), channel.data());
  n += std::snprintf(
      out + n, out_size - static_cast<std::size_t>(n), frame.extended ? "%08X#" : "%03X#",
      static_cast<unsigned>(frame.extended ? frame.id & kCanEffMask : frame.id & kCanSffMask));
  auto pos = static_cast<std::size_t>(n);
  for (std::uint8_t i = 0; i < len; ++i) {
    out[pos++] = kHexDigits[frame.data[i] >> 4];
    out[pos++] = kHexDigits[frame.data[i] & 0xF];
  }
  out[pos++] = '\n';
  out[pos] = '\0';
  return pos;
}

CandumpLogWriter::CandumpLogWriter(const std::string& path, std::string channel)
    : path_(path), channel_(std::move(channel)) {
  if (channel_.empty() || channel_.size() > kMaxChannelChars ||
      channel_.find_first_of(" \t\r\n") != std::string::npos)
    throw std::invalid_argument("candump log " + path + ": channel name '" + channel_ +
                                "' must be 1.." + std::to_string(kMaxChannelChars) +
                                " characters without spaces");
  file_ = std::make_unique<io::LineFile>(path, "candump log");
}

CandumpLogWriter::~CandumpLogWriter() {
  try {
    close();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "warning: %s\n", e.what());
  }
}

void CandumpLogWriter::write(const CanFrame& frame, std::int64_t t_ns) {
  if (t_ns < 0)
    throw std::invalid_argument("candump log " + path_ + ": negative timestamp " +
                                std::to_string(t_ns) + " ns");
  char line[40 + kMaxChannelChars + 16 + 1];
  const std::size_t n = format_candump_line(frame, t_ns, channel_, line, sizeof line);
  std::lock_guard lock(mu_);
  if (!file_) throw std::runtime_error("candump log " + path_ + ": write after close");
  file_->append(std::string_view(line, n));  // one whole line per write (line_file.h)
  ++frames_;
}

void CandumpLogWriter::flush() {
  // every line is already in the file (no user-space buffer)
}

void CandumpLogWriter::close() {
  std::lock_guard lock(mu_);
  if (!file_) return;
  const std::unique_ptr<io::LineFile> f = std::move(file_);
  f->close();
}

std::uint64_t CandumpLogWriter::frames_written() const {
  std::lock_guard lock(mu_);
  return frames_;
}

CandumpLineStatus parse_candump_line(std::string_view line, CandumpRecord& out,
                                     std::string& error) {
  while (!line.empty() && is_space(line.back()))
    line.remove_suffix(1);
  while (!line.empty() && is_space(line.front()))
    line.remove_prefix(1);
  if (line.empty() || line.front() == '#') return CandumpLineStatus::kSkip;

  std::string_view tokens[5];
  std::size_t count = 0;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i]))
      ++i;
    if (i == line.size()) break;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i]))
      ++i;
    if (count == 5) break;
    tokens[count++] = line.substr(start, i - start);
  }
  if (count < 3) {
    error = "expected '(TIME) CHANNEL ID#DATA', found " + std::to_string(count) + " field" +
            (count == 1 ? "" : "s");
    return CandumpLineStatus::kError;
  }
  if (count > 4) {
    error = "too many fields (expected '(TIME) CHANNEL ID#DATA' and an optional R or T)";
    return CandumpLineStatus::kError;
  }
  out = CandumpRecord{};
  if (count == 4) {
    const std::string_view dir = tokens[3];
    if (dir.size() != 1 || (dir[0] != 'R' && dir[0] != 'T' && dir[0] != 'r' && dir[0] != 't')) {
      error = "unexpected field " + quoted(dir) + " after the frame (only R or T is allowed)";
      return CandumpLineStatus::kError;
    }
    out.direction = (dir[0] == 'r' || dir[0] == 'R') ? 'R' : 'T';
  }
  if (!parse_timestamp(tokens[0], out.t_ns, error)) return CandumpLineStatus::kError;
  out.channel = std::string(tokens[1]);
  if (!parse_frame(tokens[2], out, error)) return CandumpLineStatus::kError;
  return CandumpLineStatus::kRecord;
}

namespace {

// `path`, once it is known to be a regular file (a FIFO would block the open for ever)
const std::string& regular_file(const std::string& path) {
  io::check_input_file(path, "candump log");
  return path;
}

}  // namespace

CandumpReader::CandumpReader(const std::string& path, bool strict, bool ignore_torn_tail)
    : path_(path),
      strict_(strict),
      ignore_torn_tail_(ignore_torn_tail),
      in_(regular_file(path), std::ios::binary) {
  if (!in_)
    throw std::runtime_error("candump log " + path + ": cannot open: " + net::errno_text(errno));
}

std::optional<CandumpRecord> CandumpReader::next() {
  CandumpRecord rec;
  std::string error;
  while (std::getline(in_, line_)) {
    ++line_number_;
    // getline stopped at the end of the file, not at a '\n': the last line is unterminated
    if (ignore_torn_tail_ && in_.eof() && !line_.empty()) {
      torn_tail_ = line_number_;
      break;
    }
    switch (parse_candump_line(line_, rec, error)) {
      case CandumpLineStatus::kRecord:
        return rec;
      case CandumpLineStatus::kSkip:
        break;
      case CandumpLineStatus::kError:
        last_error_ =
            path_ + ":" + std::to_string(line_number_) + ": " + error + ": " + quoted(line_);
        ++malformed_;
        if (strict_) throw std::runtime_error(last_error_);
        break;
    }
  }
  if (in_.bad())
    throw std::runtime_error("candump log " + path_ + ": read error after line " +
                             std::to_string(line_number_));
  return std::nullopt;
}

}  // namespace sonarloop::can
