#pragma once
// socketcand ASCII protocol pieces shared by the server and the client (docs/formats.md §4.4).
// Every element is "< ... >"; in rawmode the server sends
//   \n< frame 09F80123 1699999999.123456 00E6B523B1AC6A06 >
// (id %08X for 29-bit, %03X for 11-bit; time SEC.USEC; data uppercase hex without spaces). The
// newline goes BEFORE each frame: python-can 4.1 drops the one character after the last complete
// element it parses from a read, so without a separator a frame split across recv() calls loses
// its '<', and with a trailing "\n" several frames in one read leave a lone "\n" that it logs as
// "Bad data: No opening < found" (docs/formats.md 4.4 has the measurement). The leading "\n" is the
// character it drops. The client sends
//   < send 09F80123 8 00 E6 B5 23 B1 AC 6A 06 >
// (python-can 4.1 writes the id unpadded and the bytes as lowercase hex without zero padding:
// "< send 9F80123 8 0 e6 b5 23 b1 ac 6a 6 >"; both are accepted). An id is extended when it has
// more than 3 hex digits or is larger than 7FF.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "drivers/can/can_frame.h"
#include "drivers/can/can_transport.h"

namespace sonarloop::can {

// Longest element either side produces (a "< send >" with 8 bytes is 50 characters).
inline constexpr std::size_t kSocketcandMaxElement = 128;

// "\n< frame ... >" into out; returns the length (0 if out is too small; 80 bytes always do).
// Negative times are written as 0.
std::size_t format_socketcand_frame(const CanFrame& frame, std::int64_t t_ns, char* out,
                                    std::size_t out_size);
// "< send ... >" into out; returns the length (0 if out is too small; 64 bytes always do).
std::size_t format_socketcand_send(const CanFrame& frame, char* out, std::size_t out_size);

// Parses "< frame ID SEC.USEC DATA >". nullopt with `error` set if malformed.
std::optional<TimedCanFrame> parse_socketcand_frame(std::string_view element, std::string& error);
// Parses "< send ID DLC B0 B1 ... >". nullopt with `error` set if malformed.
std::optional<CanFrame> parse_socketcand_send(std::string_view element, std::string& error);

// The words of an element: "< open vcan0 >" -> command "open", args "vcan0".
struct SocketcandElement {
  std::string_view command;
  std::string_view args;  // the rest, trimmed
};
std::optional<SocketcandElement> split_socketcand_element(std::string_view element);

// Cuts a TCP byte stream into "< ... >" elements. Characters between elements (newlines,
// spaces) are ignored. An element longer than kSocketcandMaxElement, or any other character
// outside an element, is a protocol error.
class SocketcandStreamParser {
 public:
  // Appends received bytes.
  void append(const char* data, std::size_t size) { buffer_.append(data, size); }
  // Next complete element ("< ... >", including the brackets); nullopt if none is complete yet.
  // Sets `error` (and returns nullopt) on a protocol error; the stream is then unusable.
  std::optional<std::string> next(std::string& error);
  std::size_t buffered() const { return buffer_.size() - pos_; }

 private:
  std::string buffer_;
  std::size_t pos_ = 0;
};

}  // namespace sonarloop::can
