#pragma once
// The checks every loader test makes of a refused document: the message reads
// "<file>: <path>: ...; allowed: ...", the first issue is at `path`, and every `parts` string is
// somewhere in the message.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

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

}  // namespace sonarloop::testing
