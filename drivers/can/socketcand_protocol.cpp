#include "drivers/can/socketcand_protocol.h"

#include <charconv>
#include <cstdio>

#include "drivers/can/can_text.h"

namespace sonarloop::can {
namespace {

bool is_protocol_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_protocol_space(s.front()))
    s.remove_prefix(1);
  while (!s.empty() && is_protocol_space(s.back()))
    s.remove_suffix(1);
  return s;
}

// Next whitespace-separated word of s (s advances past it).
std::string_view next_word(std::string_view& s) {
  s = trim(s);
  std::size_t i = 0;
  while (i < s.size() && !is_protocol_space(s[i]))
    ++i;
  const std::string_view word = s.substr(0, i);
  s.remove_prefix(i);
  return word;
}

bool parse_hex(std::string_view word, std::uint32_t& value) {
  if (word.empty() || word.size() > 8) return false;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value, 16);
  return ec == std::errc() && end == word.data() + word.size();
}

// An id word: extended if it has more than 3 digits or does not fit 11 bits.
bool parse_id(std::string_view word, CanFrame& f) {
  std::uint32_t id = 0;
  if (!parse_hex(word, id) || id > kCanEffMask) return false;
  f.extended = word.size() > 3 || id > kCanSffMask;
  f.id = id;
  return true;
}

}  // namespace

std::size_t format_socketcand_frame(const CanFrame& frame, std::int64_t t_ns, char* out,
                                    std::size_t out_size) {
  if (out_size < 80) return 0;
  if (t_ns < 0) t_ns = 0;
  const std::uint8_t len = frame.len > 8 ? 8 : frame.len;
  const int n = std::snprintf(
      out, out_size, frame.extended ? "\n< frame %08X %lld.%06lld " : "\n< frame %03X %lld.%06lld ",
      static_cast<unsigned>(frame.extended ? frame.id & kCanEffMask : frame.id & kCanSffMask),
      static_cast<long long>(t_ns / kNsPerSecond),
      static_cast<long long>((t_ns % kNsPerSecond) / 1000));
  auto pos = static_cast<std::size_t>(n);
  for (std::uint8_t i = 0; i < len; ++i) {
    out[pos++] = kHexDigits[frame.data[i] >> 4];
    out[pos++] = kHexDigits[frame.data[i] & 0xF];
  }
  for (char c : std::string_view(" >"))
    out[pos++] = c;
  out[pos] = '\0';
  return pos;
}

std::size_t format_socketcand_send(const CanFrame& frame, char* out, std::size_t out_size) {
  if (out_size < 64) return 0;
  const std::uint8_t len = frame.len > 8 ? 8 : frame.len;
  int n = std::snprintf(
      out, out_size, frame.extended ? "< send %08X %X" : "< send %03X %X",
      static_cast<unsigned>(frame.extended ? frame.id & kCanEffMask : frame.id & kCanSffMask),
      static_cast<unsigned>(len));
  auto pos = static_cast<std::size_t>(n);
  for (std::uint8_t i = 0; i < len; ++i) {
    out[pos++] = ' ';
    out[pos++] = kHexDigits[frame.data[i] >> 4];
    out[pos++] = kHexDigits[frame.data[i] & 0xF];
  }
  out[pos++] = ' ';
  out[pos++] = '>';
  out[pos] = '\0';
  return pos;
}

std::optional<SocketcandElement> split_socketcand_element(std::string_view element) {
  element = trim(element);
  if (element.size() < 2 || element.front() != '<' || element.back() != '>') return std::nullopt;
  std::string_view inner = element.substr(1, element.size() - 2);
  SocketcandElement out;
  out.command = next_word(inner);
  out.args = trim(inner);
  if (out.command.empty()) return std::nullopt;
  return out;
}

std::optional<TimedCanFrame> parse_socketcand_frame(std::string_view element, std::string& error) {
  const auto el = split_socketcand_element(element);
  if (!el || el->command != "frame") {
    error = "not a '< frame ID TIME DATA >' element";
    return std::nullopt;
  }
  std::string_view args = el->args;
  const std::string_view id_word = next_word(args);
  const std::string_view time_word = next_word(args);
  const std::string_view data_word = next_word(args);
  if (!trim(args).empty()) {
    error = "too many words in a frame element";
    return std::nullopt;
  }
  TimedCanFrame out;
  if (!parse_id(id_word, out.frame)) {
    error = "bad CAN id '" + std::string(id_word) + "'";
    return std::nullopt;
  }
  // SEC.USEC (the fraction may have 0..9 digits)
  const auto dot = time_word.find('.');
  const std::string_view sec = time_word.substr(0, dot);
  const std::string_view frac =
      dot == std::string_view::npos ? std::string_view{} : time_word.substr(dot + 1);
  long long s = 0;
  const auto [end, ec] = std::from_chars(sec.data(), sec.data() + sec.size(), s);
  bool ok = !sec.empty() && ec == std::errc() && end == sec.data() + sec.size() && s >= 0 &&
            s < 9'000'000'000LL && frac.size() <= 9;
  std::int64_t ns = 0;
  for (std::size_t i = 0; ok && i < 9; ++i) {
    const char c = i < frac.size() ? frac[i] : '0';
    ok = c >= '0' && c <= '9';
    ns = ns * 10 + (c - '0');
  }
  if (!ok) {
    error = "bad timestamp '" + std::string(time_word) + "'";
    return std::nullopt;
  }
  out.t_ns = s * kNsPerSecond + ns;
  if (data_word.size() % 2 != 0 || data_word.size() > 16) {
    error = "bad data '" + std::string(data_word) + "' (0..8 bytes as hex pairs)";
    return std::nullopt;
  }
  for (std::size_t i = 0; i < data_word.size() / 2; ++i) {
    std::uint32_t b = 0;
    if (!parse_hex(data_word.substr(2 * i, 2), b)) {
      error = "bad data '" + std::string(data_word) + "' (0..8 bytes as hex pairs)";
      return std::nullopt;
    }
    out.frame.data[i] = static_cast<std::uint8_t>(b);
  }
  out.frame.len = static_cast<std::uint8_t>(data_word.size() / 2);
  return out;
}

std::optional<CanFrame> parse_socketcand_send(std::string_view element, std::string& error) {
  const auto el = split_socketcand_element(element);
  if (!el || el->command != "send") {
    error = "not a '< send ID DLC DATA... >' element";
    return std::nullopt;
  }
  std::string_view args = el->args;
  CanFrame f;
  const std::string_view id_word = next_word(args);
  if (!parse_id(id_word, f)) {
    error = "bad CAN id '" + std::string(id_word) + "'";
    return std::nullopt;
  }
  const std::string_view dlc_word = next_word(args);
  std::uint32_t dlc = 0;
  if (!parse_hex(dlc_word, dlc) || dlc > 8) {
    error = "bad length '" + std::string(dlc_word) + "' (0..8)";
    return std::nullopt;
  }
  for (std::uint32_t i = 0; i < dlc; ++i) {
    const std::string_view byte_word = next_word(args);
    std::uint32_t b = 0;
    if (byte_word.size() > 2 || !parse_hex(byte_word, b)) {
      error = "bad or missing data byte " + std::to_string(i) + " '" + std::string(byte_word) + "'";
      return std::nullopt;
    }
    f.data[i] = static_cast<std::uint8_t>(b);
  }
  if (!trim(args).empty()) {
    error = "more data bytes than the length " + std::to_string(dlc);
    return std::nullopt;
  }
  f.len = static_cast<std::uint8_t>(dlc);
  return f;
}

std::optional<std::string> SocketcandStreamParser::next(std::string& error) {
  // skip separators between elements
  while (pos_ < buffer_.size() && is_protocol_space(buffer_[pos_]))
    ++pos_;
  if (pos_ < buffer_.size() && buffer_[pos_] != '<') {
    error = "unexpected character '" + std::string(1, buffer_[pos_]) + "' outside '< ... >'";
    return std::nullopt;
  }
  std::optional<std::string> out;
  const auto close = buffer_.find('>', pos_);
  if (close != std::string::npos) {
    if (close - pos_ + 1 > kSocketcandMaxElement) {
      error = "element longer than " + std::to_string(kSocketcandMaxElement) + " characters";
      return std::nullopt;
    }
    out = buffer_.substr(pos_, close - pos_ + 1);
    pos_ = close + 1;
  } else if (buffer_.size() - pos_ > kSocketcandMaxElement) {
    error = "no '>' within " + std::to_string(kSocketcandMaxElement) + " characters";
    return std::nullopt;
  }
  // drop consumed bytes once they dominate the buffer (amortised O(1))
  if (pos_ > 4096 && pos_ * 2 > buffer_.size()) {
    buffer_.erase(0, pos_);
    pos_ = 0;
  }
  if (pos_ == buffer_.size()) {
    buffer_.clear();
    pos_ = 0;
  }
  return out;
}

}  // namespace sonarloop::can
