#pragma once
// The checks every loader test makes of a refused document: the message reads
// "<file>: <path>: ...; allowed: ...", the first issue is at `path`, and every `parts` string is
// somewhere in the message; and the loaders' robustness check against random byte edits.
#include <catch2/catch.hpp>

#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "common/rng.h"
#include "config/loader/yaml_fields.h"

namespace sonarloop::testing {

inline bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// Checks the form of `e` for a document named `file` (see the header comment).
inline config::ConfigIssue check_config_error(const config::ConfigError& e, const std::string& file,
                                              const std::string& path,
                                              const std::vector<std::string>& parts) {
  const std::string msg = e.what();
  INFO("message: " << msg);
  const std::string shown = path.empty() ? "(top level)" : path;
  CHECK(msg.rfind(file + ": " + shown + ": ", 0) == 0);
  CHECK(e.first().path == path);
  CHECK(contains(msg, "; allowed: "));
  for (const auto& p : parts)
    CHECK(contains(msg, p));
  return e.first();
}

// Calls parse(yaml, file), which must throw a ConfigError, and checks it (check_config_error).
template <class Parse>
config::ConfigIssue expect_config_error(Parse&& parse, const std::string& file,
                                        const std::string& yaml, const std::string& path,
                                        const std::vector<std::string>& parts) {
  INFO("yaml:\n" << yaml);
  try {
    parse(yaml, file);
  } catch (const config::ConfigError& e) {
    return check_config_error(e, file, path, parts);
  }
  FAIL("accepted");
  return {};
}

// 1 to 4 random byte edits of `text` (overwrite a byte, erase 1 to 5, insert one), the bytes drawn
// from characters YAML gives a meaning to, and digits and letters.
inline std::string random_byte_edits(std::string text, Rng& rng) {
  static const std::string alphabet = "{}[]:,-#&*!|>'\"%@`? \n\t.0123456789abxyz~";
  const auto edits = 1 + rng.below(4);
  for (std::uint64_t j = 0; j < edits && !text.empty(); ++j) {
    const std::size_t pos = rng.below(text.size());
    const char c = alphabet[rng.below(alphabet.size())];
    switch (rng.below(3)) {
      case 0:
        text[pos] = c;
        break;
      case 1:
        text.erase(pos, 1 + rng.below(5));
        break;
      default:
        text.insert(pos, 1, c);
        break;
    }
  }
  return text;
}

struct ByteEditOutcome {
  int accepted = 0;
  int rejected = 0;
};

// Feeds `count` randomly edited copies of `text` (random_byte_edits) to parse(edited,
// "edited.yaml"), which checks what it accepts: each copy must parse or throw a ConfigError
// whose message reads "edited.yaml: ...; allowed: ..."; any other exception, or a badly formed
// message, fails the test.
template <class Parse>
ByteEditOutcome feed_byte_edits(const std::string& text, Rng& rng, int count, Parse&& parse) {
  ByteEditOutcome out;
  for (int k = 0; k < count; ++k) {
    const std::string edited = random_byte_edits(text, rng);
    try {
      parse(edited, "edited.yaml");
      ++out.accepted;
    } catch (const config::ConfigError& e) {
      ++out.rejected;
      const std::string msg = e.what();
      if (msg.rfind("edited.yaml: ", 0) != 0 || !contains(msg, "; allowed: ")) {
        FAIL("badly formed message: " << msg);
      }
    } catch (const std::exception& e) {
      FAIL("not a ConfigError: " << e.what() << "\n" << edited);
    }
  }
  return out;
}

}  // namespace sonarloop::testing
