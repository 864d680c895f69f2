// The live view's HTTP request head parser (drivers/net/http_request.h) on the bytes a client
// sends: whatever they are, the answer is within the limits (a head taken is at most the limit
// long, within the input, its target a path), an incomplete head is never longer than the
// limit, and the answer does not depend on what comes after a whole head (pipelining). The
// first byte picks the limit, so that small limits are tried too.
#include <cstdlib>
#include <string>
#include <string_view>

#include "drivers/net/http_request.h"
#include "tests/fuzz/fuzz_support.h"

using namespace sonarloop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t max = 64 + std::size_t{data[0]} * 64;  // 64 B to 16 KiB
  const std::string_view in(reinterpret_cast<const char*>(data + 1), size - 1);
  net::HttpRequestHead head;
  std::string error;
  const net::HttpParse r = net::parse_http_request_head(in, head, error, max);
  switch (r) {
    case net::HttpParse::kIncomplete:
      if (in.size() > max || !error.empty()) std::abort();
      return 0;
    case net::HttpParse::kBad:
    case net::HttpParse::kTooLarge:
    case net::HttpParse::kVersion:
      if (error.empty()) std::abort();
      return 0;
    case net::HttpParse::kComplete:
      break;
  }
  if (head.head_bytes == 0 || head.head_bytes > in.size() || head.head_bytes > max) std::abort();
  if (head.target.empty() || head.target[0] != '/' ||
      head.target.compare(0, head.path.size(), head.path) != 0) {
    std::abort();
  }
  if (head.header_fields > net::kMaxHttpHeaderFields) std::abort();
  // the head alone gives the same answer: nothing after it was looked at
  net::HttpRequestHead alone;
  if (net::parse_http_request_head(in.substr(0, head.head_bytes), alone, error, max) !=
          net::HttpParse::kComplete ||
      alone.head_bytes != head.head_bytes || alone.target != head.target ||
      alone.keep_alive != head.keep_alive || alone.has_body != head.has_body) {
    std::abort();
  }
  return 0;
}
