#pragma once
// Internal to the YAML toolkit (yaml_fields.h): how values and positions read in messages, shared
// by its files (yaml_fields.cpp, yaml_numbers.cpp, yaml_document.cpp, yaml_suggestions.cpp).
#include <string>
#include <string_view>

#include <yaml-cpp/yaml.h>

namespace sonarloop::config::yaml_text {

// longest value text quoted in a message before it is cut with "..."
inline constexpr std::size_t kMaxQuotedChars = 60;

// control characters (a block scalar's newlines) written as escapes: one issue, one line
std::string printable(std::string_view s);
// 'text', cut at kMaxQuotedChars with "..."
std::string quote(std::string_view s);
// 1-based line/column of a mark, 0 when yaml-cpp has none
int mark_line(const YAML::Mark& m);
int mark_column(const YAML::Mark& m);
// ASCII lower case
std::string lower(std::string_view s);

}  // namespace sonarloop::config::yaml_text
