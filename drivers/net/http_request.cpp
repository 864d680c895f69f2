#include "drivers/net/http_request.h"

#include <cstdint>

namespace sonarloop::net {
namespace {

// tchar (RFC 9110 §5.6.2)
bool is_token_char(unsigned char c) {
  if (c >= '0' && c <= '9') return true;
  if ((c | 0x20) >= 'a' && (c | 0x20) <= 'z') return true;
  switch (c) {
    case '!':
    case '#':
    case '$':
    case '%':
    case '&':
    case '\'':
    case '*':
    case '+':
    case '-':
    case '.':
    case '^':
    case '_':
    case '`':
    case '|':
    case '~':
      return true;
    default:
      return false;
  }
}

bool is_token(std::string_view s) {
  if (s.empty()) return false;
  for (unsigned char c : s)
    if (!is_token_char(c)) return false;
  return true;
}

// field-value characters: VCHAR, obs-text, SP, HTAB (RFC 9110 §5.5)
bool is_field_value(std::string_view s) {
  for (unsigned char c : s)
    if (c < 0x20 ? c != '\t' : c == 0x7f) return false;
  return true;
}

// a request-target in origin form: "/" then visible ASCII (RFC 9112 §3.2.1)
bool is_origin_form(std::string_view s) {
  if (s.empty() || s[0] != '/') return false;
  for (unsigned char c : s)
    if (c <= 0x20 || c >= 0x7f) return false;
  return true;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if ((a[i] | 0x20) != (b[i] | 0x20)) return false;
  return true;
}

std::string_view trim_ows(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t'))
    s.remove_suffix(1);
  return s;
}

// Connection: a comma-separated list of tokens (RFC 9110 §7.6.1)
void apply_connection(std::string_view value, int minor_version, bool& keep_alive) {
  while (!value.empty()) {
    const std::size_t comma = value.find(',');
    const std::string_view option = trim_ows(value.substr(0, comma));
    if (iequals(option, "close")) keep_alive = false;
    if (iequals(option, "keep-alive") && minor_version == 0) keep_alive = true;
    if (comma == std::string_view::npos) break;
    value.remove_prefix(comma + 1);
  }
}

// Content-Length: 1*DIGIT (RFC 9110 §8.6); -1 when not a length
std::int64_t content_length(std::string_view value) {
  if (value.empty() || value.size() > 18) return -1;
  std::int64_t n = 0;
  for (char c : value) {
    if (c < '0' || c > '9') return -1;
    n = n * 10 + (c - '0');
  }
  return n;
}

struct Line {
  std::string_view text;  // without CRLF / LF
  std::size_t end = 0;    // offset just past the LF
};

// The line starting at `from`; false when no LF has come yet.
bool next_line(std::string_view in, std::size_t from, Line& line) {
  const std::size_t lf = in.find('\n', from);
  if (lf == std::string_view::npos) return false;
  std::string_view text = in.substr(from, lf - from);
  if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
  line = {text, lf + 1};
  return true;
}

HttpParse bad(std::string& error, const char* what) {
  error = what;
  return HttpParse::kBad;
}

HttpParse parse_request_line(std::string_view line, HttpRequestHead& head, std::string& error) {
  const std::size_t sp1 = line.find(' ');
  const std::size_t sp2 = sp1 == std::string_view::npos ? sp1 : line.find(' ', sp1 + 1);
  if (sp2 == std::string_view::npos) return bad(error, "request line is not METHOD TARGET VERSION");
  const std::string_view method = line.substr(0, sp1);
  const std::string_view target = line.substr(sp1 + 1, sp2 - sp1 - 1);
  const std::string_view version = line.substr(sp2 + 1);
  if (!is_token(method)) return bad(error, "method is not a token");
  if (version.size() != 8 || version.substr(0, 5) != "HTTP/" || version[6] != '.' ||
      version[5] < '0' || version[5] > '9' || version[7] < '0' || version[7] > '9') {
    return bad(error, "version is not HTTP/d.d");
  }
  if (version[5] != '1' || (version[7] != '0' && version[7] != '1')) {
    error = "only HTTP/1.0 and HTTP/1.1 are served";
    return HttpParse::kVersion;
  }
  if (!is_origin_form(target)) return bad(error, "target is not a path starting with /");
  head.method = method;
  head.target = target;
  head.path = target.substr(0, target.find_first_of("?#"));
  head.minor_version = version[7] - '0';
  head.keep_alive = head.minor_version == 1;
  return HttpParse::kComplete;
}

}  // namespace

HttpParse parse_http_request_head(std::string_view received, HttpRequestHead& head,
                                  std::string& error, std::size_t max_head_bytes) {
  head = HttpRequestHead{};
  error.clear();
  const auto too_large = [&] {
    error = "request head longer than " + std::to_string(max_head_bytes) + " bytes";
    return HttpParse::kTooLarge;
  };
  // the limit holds for what was received, whether or not a line has ended in it
  const auto incomplete = [&] {
    return received.size() > max_head_bytes ? too_large() : HttpParse::kIncomplete;
  };

  // a server should ignore empty lines before the request line (RFC 9112 §2.2)
  std::size_t at = 0;
  Line line;
  for (;;) {
    if (!next_line(received, at, line)) return incomplete();
    if (line.end > max_head_bytes) return too_large();
    if (!line.text.empty()) break;
    at = line.end;
  }
  if (const HttpParse r = parse_request_line(line.text, head, error); r != HttpParse::kComplete) {
    return r;
  }
  at = line.end;

  bool have_host = false;
  std::int64_t length = -1;
  for (;;) {
    if (!next_line(received, at, line)) return incomplete();
    if (line.end > max_head_bytes) return too_large();
    at = line.end;
    if (line.text.empty()) break;
    if (++head.header_fields > kMaxHttpHeaderFields) {
      error = "more than " + std::to_string(kMaxHttpHeaderFields) + " header fields";
      return HttpParse::kTooLarge;
    }
    if (line.text[0] == ' ' || line.text[0] == '\t') {
      return bad(error, "folded header line (obsolete, RFC 9112 §5.2)");
    }
    const std::size_t colon = line.text.find(':');
    if (colon == std::string_view::npos) return bad(error, "header line without a colon");
    const std::string_view name = line.text.substr(0, colon);
    const std::string_view value = trim_ows(line.text.substr(colon + 1));
    if (!is_token(name)) return bad(error, "header name is not a token");
    if (!is_field_value(value)) return bad(error, "control character in a header value");
    if (iequals(name, "Host")) {
      if (have_host) return bad(error, "two Host header fields");
      have_host = true;
    } else if (iequals(name, "Connection")) {
      apply_connection(value, head.minor_version, head.keep_alive);
    } else if (iequals(name, "Content-Length")) {
      const std::int64_t n = content_length(value);
      if (n < 0 || (length >= 0 && n != length)) return bad(error, "bad Content-Length");
      length = n;
      if (n > 0) head.has_body = true;
    } else if (iequals(name, "Transfer-Encoding")) {
      head.has_body = true;
    }
  }
  // a server must answer 400 to an HTTP/1.1 request without Host (RFC 9112 §3.2)
  if (head.minor_version == 1 && !have_host) return bad(error, "HTTP/1.1 request without Host");
  head.head_bytes = at;
  return HttpParse::kComplete;
}

}  // namespace sonarloop::net
