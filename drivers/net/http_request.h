#pragma once
// The head of one HTTP/1.x request (RFC 9112 §2-§6), parsed from the bytes a connection has
// received so far: what the live view's server (web/web_server.h) needs and nothing more. It
// serves GET and HEAD of three paths, so a request body is refused rather than read.
//
// Pure and bounded: the whole head (request line and header fields up to the empty line) may
// be at most `max_head_bytes` long with at most kMaxHttpHeaderFields fields, so a client that
// sends an endless request line or header block gets kTooLarge as soon as the limit is
// passed, and the server never holds more than the limit for it. A head that is incomplete
// but within the limits gives kIncomplete: wait for more bytes (the server bounds the time).
#include <cstddef>
#include <string>
#include <string_view>

namespace sonarloop::net {

// Enough for a browser's request with the cookies other pages on the same host may set
// (nginx's default allows 4 x 8 KiB; Apache 8 KiB per field).
inline constexpr std::size_t kDefaultMaxHttpHeadBytes = 16384;
inline constexpr int kMaxHttpHeaderFields = 100;

struct HttpRequestHead {
  std::string method;      // as sent ("GET"); methods are case-sensitive (RFC 9110 §9.1)
  std::string target;      // origin form: "/stats.json?x=1" as sent
  std::string path;        // the target up to '?' or '#'
  int minor_version = 1;   // HTTP/1.0 or HTTP/1.1
  bool keep_alive = true;  // HTTP/1.1 unless "Connection: close"; HTTP/1.0 only with keep-alive
  bool has_body = false;   // Content-Length > 0 or a Transfer-Encoding: the server refuses it
  int header_fields = 0;
  std::size_t head_bytes = 0;  // through the empty line: where the next request starts
};

enum class HttpParse {
  kComplete,    // `head` holds the request; `head.head_bytes` of the input were its head
  kIncomplete,  // no empty line yet, within the limits
  kBad,         // not HTTP/1.x or malformed (400); `error` says what
  kTooLarge,    // the head passes max_head_bytes or kMaxHttpHeaderFields (431)
  kVersion,     // HTTP/2 and later, or HTTP/0.x (505)
};

// Parses the request at the start of `received`. Lines end in CRLF or a bare LF (RFC 9112
// §2.2 allows a recipient to accept LF); a field name is a token; obsolete line folding, a
// space before the colon, a bad or repeated-and-different Content-Length are errors (RFC 9112
// §5.1, §5.2, §6.3), as is a target that is not in origin form.
HttpParse parse_http_request_head(std::string_view received, HttpRequestHead& head,
                                  std::string& error,
                                  std::size_t max_head_bytes = kDefaultMaxHttpHeadBytes);

}  // namespace sonarloop::net
