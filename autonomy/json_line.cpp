#include "autonomy/json_line.h"

#include <cctype>
#include <cstdlib>

namespace sonarloop::autonomy {
namespace {

class Scanner {
 public:
  explicit Scanner(std::string_view s) : s_(s) {}
  void skip_ws() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_])))
      ++i_;
  }
  bool eat(char c) {
    skip_ws();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  bool at_end() {
    skip_ws();
    return i_ == s_.size();
  }
  // A string literal, unescaped (\uXXXX below 0x80 only; others become '?').
  std::optional<std::string> string() {
    if (!eat('"')) return std::nullopt;
    std::string out;
    while (i_ < s_.size() && s_[i_] != '"') {
      char c = s_[i_++];
      if (c == '\\') {
        if (i_ >= s_.size()) return std::nullopt;
        const char e = s_[i_++];
        switch (e) {
          case 'n':
            c = '\n';
            break;
          case 't':
            c = '\t';
            break;
          case 'r':
            c = '\r';
            break;
          case 'b':
            c = '\b';
            break;
          case 'f':
            c = '\f';
            break;
          case 'u': {
            if (i_ + 4 > s_.size()) return std::nullopt;
            const long v = std::strtol(std::string(s_.substr(i_, 4)).c_str(), nullptr, 16);
            i_ += 4;
            c = v < 0x80 ? static_cast<char>(v) : '?';
            break;
          }
          default:
            c = e;  // \" \\ \/
        }
      }
      out.push_back(c);
    }
    if (i_ >= s_.size()) return std::nullopt;
    ++i_;
    return out;
  }
  // The raw texts of an array's elements.
  std::optional<std::vector<std::string>> array() {
    std::vector<std::string> out;
    if (!eat('[')) return std::nullopt;
    if (eat(']')) return out;
    for (;;) {
      auto v = value();
      if (!v) return std::nullopt;
      out.push_back(std::move(*v));
      if (eat(',')) continue;
      if (eat(']')) return out;
      return std::nullopt;
    }
  }
  // The raw text of any value (a string's is returned quoted and unescaped).
  std::optional<std::string> value() {
    skip_ws();
    if (i_ >= s_.size()) return std::nullopt;
    if (s_[i_] == '"') {
      auto str = string();
      if (!str) return std::nullopt;
      return '"' + *str + '"';
    }
    if (s_[i_] == '{' || s_[i_] == '[') return nested();
    const std::size_t b = i_;
    while (i_ < s_.size() && s_[i_] != ',' && s_[i_] != '}' && s_[i_] != ']' &&
           !std::isspace(static_cast<unsigned char>(s_[i_])))
      ++i_;
    if (i_ == b) return std::nullopt;
    return std::string(s_.substr(b, i_ - b));
  }

 private:
  // A nested object or array, as its text (brackets balanced outside strings).
  std::optional<std::string> nested() {
    const std::size_t b = i_;
    int depth = 0;
    bool in_string = false;
    for (; i_ < s_.size(); ++i_) {
      const char c = s_[i_];
      if (in_string) {
        if (c == '\\')
          ++i_;
        else if (c == '"')
          in_string = false;
        continue;
      }
      if (c == '"')
        in_string = true;
      else if (c == '{' || c == '[')
        ++depth;
      else if ((c == '}' || c == ']') && --depth == 0) {
        ++i_;
        return std::string(s_.substr(b, i_ - b));
      }
    }
    return std::nullopt;
  }

  std::string_view s_;
  std::size_t i_ = 0;
};

}  // namespace

std::optional<JsonLine> JsonLine::parse(std::string_view text, std::string& error) {
  Scanner sc(text);
  JsonLine out;
  if (!sc.eat('{')) {
    error = "not a JSON object";
    return std::nullopt;
  }
  if (!sc.eat('}')) {
    for (;;) {
      const auto key = sc.string();
      if (!key || !sc.eat(':')) {
        error = "expected \"key\": in the object";
        return std::nullopt;
      }
      auto v = sc.value();
      if (!v) {
        error = "bad value of \"" + *key + "\"";
        return std::nullopt;
      }
      out.members_[*key] = std::move(*v);
      if (sc.eat(',')) continue;
      if (sc.eat('}')) break;
      error = "expected , or } after \"" + *key + "\"";
      return std::nullopt;
    }
  }
  if (!sc.at_end()) {
    error = "text after the object";
    return std::nullopt;
  }
  return out;
}

bool JsonLine::present(const std::string& key) const {
  const auto it = members_.find(key);
  return it != members_.end() && it->second != "null";
}

std::optional<double> JsonLine::number(const std::string& key) const {
  const auto it = members_.find(key);
  if (it == members_.end() || it->second.empty()) return std::nullopt;
  const char c = it->second[0];
  if (!(c == '-' || (c >= '0' && c <= '9'))) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (end == it->second.c_str() || *end != '\0') return std::nullopt;
  return v;
}

std::optional<std::string> JsonLine::string(const std::string& key) const {
  const auto it = members_.find(key);
  if (it == members_.end() || it->second.size() < 2 || it->second.front() != '"') {
    return std::nullopt;
  }
  return it->second.substr(1, it->second.size() - 2);
}

std::optional<bool> JsonLine::boolean(const std::string& key) const {
  const auto it = members_.find(key);
  if (it == members_.end()) return std::nullopt;
  if (it->second == "true") return true;
  if (it->second == "false") return false;
  return std::nullopt;
}

std::optional<JsonLine> JsonLine::object(const std::string& key) const {
  const auto it = members_.find(key);
  if (it == members_.end() || it->second.empty() || it->second.front() != '{') return std::nullopt;
  std::string error;
  return parse(it->second, error);
}

std::vector<JsonLine> JsonLine::objects(const std::string& key) const {
  std::vector<JsonLine> out;
  const auto it = members_.find(key);
  if (it == members_.end()) return out;
  Scanner sc(it->second);
  const auto items = sc.array();
  if (!items) return out;
  for (const std::string& item : *items) {
    std::string error;
    if (auto j = parse(item, error)) out.push_back(std::move(*j));
  }
  return out;
}

}  // namespace sonarloop::autonomy
