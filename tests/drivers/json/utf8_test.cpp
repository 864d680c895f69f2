// UTF-8 validity (RFC 3629, its Table 3-7 of well-formed sequences) and the printable form of
// names that are not valid.
#include "drivers/json/utf8.h"

#include <catch2/catch.hpp>
#include <string>

using sonarloop::json::is_valid_utf8;
using sonarloop::json::printable_bytes;

TEST_CASE("utf8: well-formed sequences pass; overlong, surrogate, cut and stray bytes do not") {
  CHECK(is_valid_utf8(""));
  CHECK(is_valid_utf8("cylinder"));
  CHECK(is_valid_utf8("\xC3\xA9pave"));            // é
  CHECK(is_valid_utf8("\xE2\x82\xAC"));            // €
  CHECK(is_valid_utf8("\xED\x9F\xBF"));            // U+D7FF, the last before the surrogates
  CHECK(is_valid_utf8("\xF0\x9F\x90\x9F"));        // U+1F41F
  CHECK(is_valid_utf8("\xF4\x8F\xBF\xBF"));        // U+10FFFF, the last code point
  CHECK_FALSE(is_valid_utf8("\xFF"));              // never in UTF-8
  CHECK_FALSE(is_valid_utf8("ab\x80"));            // a continuation byte alone
  CHECK_FALSE(is_valid_utf8("\xC0\xAF"));          // overlong '/'
  CHECK_FALSE(is_valid_utf8("\xE0\x80\xAF"));      // overlong, three bytes
  CHECK_FALSE(is_valid_utf8("\xED\xA0\x80"));      // U+D800, a surrogate
  CHECK_FALSE(is_valid_utf8("\xF4\x90\x80\x80"));  // beyond U+10FFFF
  CHECK_FALSE(is_valid_utf8("\xE2\x82"));          // cut short
  CHECK_FALSE(is_valid_utf8("\xC3("));             // a lead byte without its continuation
}

TEST_CASE("utf8: printable_bytes writes every byte outside printable ASCII as \\xNN") {
  CHECK(printable_bytes("rock") == "rock");
  CHECK(printable_bytes("a\xFF"
                        "b\n") == "a\\xFFb\\x0A");
}
