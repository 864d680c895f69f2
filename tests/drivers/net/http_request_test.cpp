// The HTTP/1.x request head parser (drivers/net/http_request.h): the requests browsers and curl
// send, the limits (an endless request line or header block is refused as soon as it passes
// them), and the malformed heads RFC 9112 says a server must refuse.
#include "drivers/net/http_request.h"

#include <catch2/catch.hpp>

using namespace sonarloop::net;

namespace {

HttpParse parse(const std::string& in, HttpRequestHead& head, std::size_t max = 16384) {
  std::string error;
  const HttpParse r = parse_http_request_head(in, head, error, max);
  if (r == HttpParse::kComplete || r == HttpParse::kIncomplete) {
    CHECK(error.empty());
  } else {
    CHECK(!error.empty());
  }
  return r;
}

HttpParse parse(const std::string& in, std::size_t max = 16384) {
  HttpRequestHead head;
  return parse(in, head, max);
}

}  // namespace

TEST_CASE("a browser's request: method, target, path, keep-alive and where it ends") {
  const std::string req =
      "GET /stats.json?t=1 HTTP/1.1\r\nHost: 127.0.0.1:8080\r\nUser-Agent: x\r\n"
      "Accept: */*\r\n\r\n";
  HttpRequestHead head;
  REQUIRE(parse(req + "GET / HTTP/1.1\r\n", head) == HttpParse::kComplete);
  CHECK(head.method == "GET");
  CHECK(head.target == "/stats.json?t=1");
  CHECK(head.path == "/stats.json");
  CHECK(head.minor_version == 1);
  CHECK(head.keep_alive);
  CHECK(!head.has_body);
  CHECK(head.header_fields == 3);
  CHECK(head.head_bytes == req.size());  // the pipelined request after it is not taken

  // bare LF line ends, empty lines before the request line, a fragment in the target
  REQUIRE(parse("\r\n\nHEAD /#x HTTP/1.1\nhost:a\n\n", head) == HttpParse::kComplete);
  CHECK(head.method == "HEAD");
  CHECK(head.path == "/");
  CHECK(head.head_bytes == 29);
}

TEST_CASE("Connection: close and HTTP/1.0 keep-alive, Content-Length and Transfer-Encoding") {
  HttpRequestHead head;
  REQUIRE(parse("GET / HTTP/1.1\r\nHost: a\r\nConnection: Keep-Alive, CLOSE\r\n\r\n", head) ==
          HttpParse::kComplete);
  CHECK(!head.keep_alive);
  REQUIRE(parse("GET / HTTP/1.0\r\n\r\n", head) == HttpParse::kComplete);  // no Host needed
  CHECK(head.minor_version == 0);
  CHECK(!head.keep_alive);
  REQUIRE(parse("GET / HTTP/1.0\r\nConnection: keep-alive\r\n\r\n", head) == HttpParse::kComplete);
  CHECK(head.keep_alive);

  REQUIRE(parse("POST / HTTP/1.1\r\nHost: a\r\nContent-Length: 0\r\n\r\n", head) ==
          HttpParse::kComplete);
  CHECK(!head.has_body);
  REQUIRE(parse("POST / HTTP/1.1\r\nHost: a\r\nContent-Length: 12\r\n\r\n", head) ==
          HttpParse::kComplete);
  CHECK(head.has_body);
  REQUIRE(parse("POST / HTTP/1.1\r\nHost: a\r\nTransfer-Encoding: chunked\r\n\r\n", head) ==
          HttpParse::kComplete);
  CHECK(head.has_body);
  // lengths that are not one decimal number (RFC 9112 §6.3: a server must refuse them)
  CHECK(parse("GET / HTTP/1.1\r\nHost: a\r\nContent-Length: -1\r\n\r\n") == HttpParse::kBad);
  CHECK(parse("GET / HTTP/1.1\r\nHost: a\r\nContent-Length: 1\r\nContent-Length: 2\r\n\r\n") ==
        HttpParse::kBad);
  CHECK(parse("GET / HTTP/1.1\r\nHost: a\r\nContent-Length: 99999999999999999999\r\n\r\n") ==
        HttpParse::kBad);
}

TEST_CASE("an incomplete head waits for more; one past the limits is refused at once") {
  CHECK(parse("") == HttpParse::kIncomplete);
  CHECK(parse("GET / HT") == HttpParse::kIncomplete);
  CHECK(parse("GET / HTTP/1.1\r\nHost: a\r\n") == HttpParse::kIncomplete);

  // an endless request line: refused when it passes the limit, before any line end
  CHECK(parse("GET /" + std::string(1000, 'a'), 1000) == HttpParse::kTooLarge);
  CHECK(parse("GET /" + std::string(990, 'a'), 1000) == HttpParse::kIncomplete);
  // an endless header block
  std::string block = "GET / HTTP/1.1\r\nHost: a\r\n";
  while (block.size() <= 1000)
    block += "X-a: b\r\n";
  CHECK(parse(block, 1000) == HttpParse::kTooLarge);
  // a head that fits exactly is taken; one byte more is not
  const std::string exact = "GET / HTTP/1.1\r\nHost: a\r\n\r\n";
  CHECK(parse(exact, exact.size()) == HttpParse::kComplete);
  CHECK(parse(exact, exact.size() - 1) == HttpParse::kTooLarge);
  // too many fields, each short
  std::string many = "GET / HTTP/1.1\r\nHost: a\r\n";
  for (int i = 1; i < kMaxHttpHeaderFields; ++i)
    many += "X: y\r\n";
  CHECK(parse(many + "\r\n") == HttpParse::kComplete);
  CHECK(parse(many + "X: y\r\n\r\n") == HttpParse::kTooLarge);
}

TEST_CASE("malformed heads and other versions are refused with a reason") {
  CHECK(parse("GET /\r\n\r\n") == HttpParse::kBad);                              // HTTP/0.9 form
  CHECK(parse("GET  / HTTP/1.1\r\nHost: a\r\n\r\n") == HttpParse::kBad);         // two spaces
  CHECK(parse("GET http://a/ HTTP/1.1\r\nHost: a\r\n\r\n") == HttpParse::kBad);  // not origin
  CHECK(parse("GET / HTTP/1.1\r\n\r\n") == HttpParse::kBad);                     // no Host
  CHECK(parse("GET / HTTP/1.1\r\nHost: a\r\nHost: b\r\n\r\n") == HttpParse::kBad);
  CHECK(parse("GET / HTTP/1.1\r\nHost : a\r\n\r\n") == HttpParse::kBad);  // space before :
  CHECK(parse("GET / HTTP/1.1\r\nHost: a\r\n folded\r\n\r\n") == HttpParse::kBad);
  CHECK(parse("GET / HTTP/1.1\r\nHost: a\r\nNo colon\r\n\r\n") == HttpParse::kBad);
  constexpr char kNul[] = "GET / HTTP/1.1\r\nHost: a\0b\r\n\r\n";
  CHECK(parse(std::string(kNul, sizeof kNul - 1)) == HttpParse::kBad);
  CHECK(parse("G@T / HTTP/1.1\r\nHost: a\r\n\r\n") == HttpParse::kBad);
  CHECK(parse("GET /a\x01 HTTP/1.1\r\nHost: a\r\n\r\n") == HttpParse::kBad);
  CHECK(parse("GET / http/1.1\r\nHost: a\r\n\r\n") == HttpParse::kBad);
  CHECK(parse("GET / HTTP/2.0\r\nHost: a\r\n\r\n") == HttpParse::kVersion);
  CHECK(parse("GET / HTTP/1.2\r\nHost: a\r\n\r\n") == HttpParse::kVersion);
  // a header value may hold obs-text and tabs
  CHECK(parse("GET / HTTP/1.1\r\nHost: a\r\nX: \xe9t\xe9\t!\r\n\r\n") == HttpParse::kComplete);
}
