#include "config/loader/yaml_text.h"

#include <cctype>

namespace sonarloop::config::yaml_text {

std::string printable(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += '?';
    } else {
      out += c;
    }
  }
  return out;
}

std::string quote(std::string_view s) {
  // appended piece by piece: GCC 12 at -O3 warns falsely (-Wrestrict) on "'" + std::string
  const bool cut = s.size() > kMaxQuotedChars;
  std::string out = "'";
  out += printable(cut ? s.substr(0, kMaxQuotedChars) : s);
  out += cut ? "...'" : "'";
  return out;
}

int mark_line(const YAML::Mark& m) {
  return m.is_null() || m.line < 0 ? 0 : m.line + 1;
}
int mark_column(const YAML::Mark& m) {
  return m.is_null() || m.column < 0 ? 0 : m.column + 1;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace sonarloop::config::yaml_text
