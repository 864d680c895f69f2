#include "config/loader/yaml_fields.h"

// The Field of yaml_fields.h: structure, maps, lists, text and names (numbers are in
// yaml_numbers.cpp, documents in yaml_document.cpp, suggestions in yaml_suggestions.cpp), and
// ConfigIssue / ConfigError.
#include <algorithm>
#include <optional>

#include "config/loader/yaml_text.h"

namespace sonarloop::config {
namespace {

using yaml_text::kMaxQuotedChars;
using yaml_text::mark_column;
using yaml_text::mark_line;
using yaml_text::printable;
using yaml_text::quote;

// nesting shown when a list or map is printed in a message
constexpr int kMaxShownDepth = 3;

std::string display_path(const std::string& path) {
  return path.empty() ? "(top level)" : path;
}

std::string child_path(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

// bounded flow-style rendering of a node (aliases can make a node contain itself)
void render(const YAML::Node& n, int depth, std::string& out) {
  if (out.size() > kMaxQuotedChars) return;
  switch (n.Type()) {
    case YAML::NodeType::Scalar:
      out += n.Scalar();
      return;
    case YAML::NodeType::Sequence: {
      if (depth >= kMaxShownDepth) {
        out += "[...]";
        return;
      }
      out += "[";
      bool first = true;
      for (const auto& item : n) {
        if (!first) out += ", ";
        first = false;
        if (out.size() > kMaxQuotedChars) break;
        render(item, depth + 1, out);
      }
      out += "]";
      return;
    }
    case YAML::NodeType::Map: {
      if (depth >= kMaxShownDepth) {
        out += "{...}";
        return;
      }
      out += "{";
      bool first = true;
      for (const auto& kv : n) {
        if (!first) out += ", ";
        first = false;
        if (out.size() > kMaxQuotedChars) break;
        render(kv.first, depth + 1, out);
        out += ": ";
        render(kv.second, depth + 1, out);
      }
      out += "}";
      return;
    }
    default:
      out += "~";
      return;
  }
}

std::string rendered(const YAML::Node& n) {
  std::string out;
  render(n, 0, out);
  if (out.size() > kMaxQuotedChars) out = out.substr(0, kMaxQuotedChars) + "...";
  return printable(out);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// ConfigIssue / ConfigError

std::string ConfigIssue::message() const {
  std::string m =
      (file.empty() ? std::string("<input>") : file) + ": " + display_path(path) + ": " + problem;
  if (line > 0) {
    m += " (line " + std::to_string(line) + ", column " + std::to_string(column) + ")";
  }
  m += "; allowed: " + allowed;
  if (!suggestion.empty()) m += " (did you mean '" + suggestion + "'?)";
  return m;
}

namespace {
std::string join_messages(const std::vector<ConfigIssue>& issues) {
  std::string out;
  for (const auto& i : issues) {
    if (!out.empty()) out += "\n";
    out += i.message();
  }
  return out;
}
}  // namespace

ConfigError::ConfigError(ConfigIssue issue)
    : ConfigError(std::vector<ConfigIssue>{std::move(issue)}) {}

ConfigError::ConfigError(std::vector<ConfigIssue> issues)
    : std::runtime_error(join_messages(issues)), issues_(std::move(issues)) {
  if (issues_.empty()) {
    issues_.push_back({"<input>", "", "unspecified configuration error", "-", {}, 0, 0});
  }
}
// ---------------------------------------------------------------------------------------------
// Field: construction and structure

Field::Field(YAML::Node node, std::string file, std::shared_ptr<const std::string> text)
    : node_(std::move(node)), file_(std::move(file)), text_(std::move(text)) {
  line_ = mark_line(node_.Mark());
  column_ = mark_column(node_.Mark());
  attach_state(nullptr);
}

Field Field::make_child(std::string path, YAML::Node value, const YAML::Mark& fallback,
                        bool present, std::shared_ptr<NodeState>* slot) const {
  Field f;
  f.file_ = file_;
  f.text_ = text_;
  f.path_ = std::move(path);
  f.present_ = present;
  if (present) {
    f.node_ = std::move(value);
    // a null value has no position of its own worth showing: point at its key
    const YAML::Mark m = (f.node_.IsNull() || f.node_.Mark().is_null()) ? fallback : f.node_.Mark();
    f.line_ = mark_line(m);
    f.column_ = mark_column(m);
    f.attach_state(slot);
  } else {
    f.node_ = YAML::Node(YAML::NodeType::Null);
    f.line_ = line_;
    f.column_ = column_;
  }
  return f;
}

void Field::attach_state(std::shared_ptr<NodeState>* slot) {
  if (!node_.IsMap() && !node_.IsSequence()) return;
  if (slot && *slot) {
    state_ = *slot;
    return;
  }
  auto state = std::make_shared<NodeState>();
  if (node_.IsSequence()) {
    state->items.resize(node_.size());
  } else {
    for (const auto& kv : node_) {
      const YAML::Node& key = kv.first;
      if (!key.IsScalar()) {
        const Field k = make_child(path_, key, key.Mark(), true, nullptr);
        k.fail(key.IsNull() ? std::string("an empty key") : "a key that is " + k.describe_value(),
               "keys are plain names");
      }
      for (const auto& e : state->entries) {
        if (e.key == key.Scalar()) {
          const Field k = make_child(child_path(path_, e.key), key, key.Mark(), true, nullptr);
          k.fail("duplicate key " + quote(e.key) + " (first at line " +
                     std::to_string(mark_line(e.key_node.Mark())) + ")",
                 "each key once per map");
        }
      }
      state->entries.push_back({key.Scalar(), key, kv.second, nullptr});
    }
  }
  state_ = state;
  if (slot) *slot = std::move(state);
}

bool Field::is_null() const {
  return !present_ || !node_.IsDefined() || node_.IsNull();
}
bool Field::is_map() const {
  return present_ && node_.IsMap();
}
bool Field::is_list() const {
  return present_ && node_.IsSequence();
}
bool Field::is_scalar() const {
  return present_ && node_.IsScalar();
}

std::string Field::describe_value() const {
  if (!present_) return "missing";
  if (is_null()) return "empty";
  if (node_.IsScalar()) return quote(node_.Scalar());
  if (node_.IsSequence()) return "a list " + rendered(node_);
  if (node_.IsMap()) return "a map " + rendered(node_);
  return "an unknown kind of node";
}

ConfigIssue Field::issue(std::string problem, std::string allowed, std::string suggestion) const {
  ConfigIssue i;
  i.file = file_;
  i.path = path_;
  i.problem = std::move(problem);
  i.allowed = std::move(allowed);
  i.suggestion = std::move(suggestion);
  i.line = line_;
  i.column = column_;
  return i;
}

void Field::fail(std::string problem, std::string allowed, std::string suggestion) const {
  throw ConfigError(issue(std::move(problem), std::move(allowed), std::move(suggestion)));
}

// ---------------------------------------------------------------------------------------------
// Field: maps

void Field::expect_map(std::string_view allowed) const {
  if (is_null() || node_.IsMap()) return;
  fail(describe_value() + " is not a map", std::string(allowed));
}

void Field::declare(std::initializer_list<std::string_view> keys) const {
  expect_map();
  if (!state_) return;
  auto& declared = state_->declared;
  for (auto k : keys) {
    if (std::find(declared.begin(), declared.end(), k) == declared.end()) declared.emplace_back(k);
  }
}

Field::MapEntry* Field::find_entry(std::string_view key) const {
  if (!state_) return nullptr;
  for (auto& e : state_->entries) {
    if (e.key == key) return &e;
  }
  return nullptr;
}

bool Field::has(std::string_view key) const {
  declare({key});
  return find_entry(key) != nullptr;
}

Field Field::child(std::string_view key) const {
  declare({key});
  if (MapEntry* e = find_entry(key)) {
    return make_child(child_path(path_, key), e->value, e->key_node.Mark(), true, &e->value_state);
  }
  return make_child(child_path(path_, key), YAML::Node(), YAML::Mark::null_mark(), false, nullptr);
}

void Field::finish() const {
  if (!state_) return;
  const auto& declared = state_->declared;
  std::vector<ConfigIssue> issues;
  for (const auto& e : state_->entries) {
    if (std::find(declared.begin(), declared.end(), e.key) != declared.end()) continue;
    const Field k =
        make_child(child_path(path_, e.key), e.key_node, e.key_node.Mark(), true, nullptr);
    issues.push_back(k.issue("unknown key " + quote(e.key),
                             declared.empty() ? "no keys here" : join_names(declared),
                             closest_name(e.key, declared).value_or("")));
  }
  if (!issues.empty()) throw ConfigError(std::move(issues));
}
// ---------------------------------------------------------------------------------------------
// Field: other values

bool Field::get_bool(std::string_view key, bool def) const {
  const Field f = child(key);
  return f.present() ? f.as_bool() : def;
}

std::string Field::get_string(std::string_view key, const std::string& def) const {
  const Field f = child(key);
  return f.present() ? f.as_string() : def;
}

bool Field::as_bool() const {
  const std::string allowed = "true or false";
  if (is_null()) fail("has no value", allowed);
  if (!node_.IsScalar()) fail(describe_value() + " is not true or false", allowed);
  const std::string& text = node_.Scalar();
  if (node_.Tag() == "!") fail(quote(text) + " is a quoted string, not true or false", allowed);
  if (text == "true" || text == "True" || text == "TRUE") return true;
  if (text == "false" || text == "False" || text == "FALSE") return false;
  fail(quote(text) + " is not true or false", allowed);
}

namespace {

// Byte index of the first byte that does not start a valid UTF-8 sequence (RFC 3629: no
// overlong forms, no surrogates, nothing above U+10FFFF); nullopt if the text is valid.
std::optional<std::size_t> invalid_utf8_at(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto b = static_cast<unsigned char>(s[i]);
    std::size_t len = 0;
    unsigned lo = 0x80, hi = 0xBF;  // allowed range of the second byte
    if (b < 0x80) {
      len = 1;
    } else if (b >= 0xC2 && b <= 0xDF) {
      len = 2;
    } else if (b >= 0xE0 && b <= 0xEF) {
      len = 3;
      if (b == 0xE0) lo = 0xA0;
      if (b == 0xED) hi = 0x9F;
    } else if (b >= 0xF0 && b <= 0xF4) {
      len = 4;
      if (b == 0xF0) lo = 0x90;
      if (b == 0xF4) hi = 0x8F;
    } else {
      return i;
    }
    if (i + len > s.size()) return i;
    for (std::size_t k = 1; k < len; ++k) {
      const auto c = static_cast<unsigned char>(s[i + k]);
      if (c < (k == 1 ? lo : 0x80u) || c > (k == 1 ? hi : 0xBFu)) return i;
    }
    i += len;
  }
  return std::nullopt;
}

// Whether a source line reads like a map key: optional indent, a word, ':' then a blank or the
// end ("seed: 1", "  sonar:").
std::optional<std::string> key_of_line(std::string_view line) {
  std::size_t i = 0;
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
    ++i;
  const std::size_t start = i;
  while (i < line.size() && (std::isalnum(static_cast<unsigned char>(line[i])) || line[i] == '_'))
    ++i;
  if (i == start || i >= line.size() || line[i] != ':') return std::nullopt;
  if (i + 1 < line.size() && line[i + 1] != ' ' && line[i + 1] != '\t' && line[i + 1] != '\r')
    return std::nullopt;
  return std::string(line.substr(start, i - start + 1));
}

struct RunawayQuote {
  int line_offset = 0;  // lines after the quote's own line
  std::string key;      // "seed:"
};

// A quoted scalar opening at text[pos]: its closing quote is searched for (escapes skipped) and
// every line it runs over is checked for a key. nullopt: closed on its own line, or only
// continuation lines that are not keys (a legitimate multi-line quoted text).
std::optional<RunawayQuote> runaway_quote(const std::string& text, std::size_t pos) {
  if (pos >= text.size() || (text[pos] != '"' && text[pos] != '\'')) return std::nullopt;
  const char q = text[pos];
  int lines = 0;
  for (std::size_t i = pos + 1; i < text.size(); ++i) {
    const char c = text[i];
    if (q == '"' && c == '\\') {
      ++i;  // an escaped character, whatever it is
      continue;
    }
    if (c == q) {
      if (q == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
        ++i;  // '' is a quote inside single quotes
        continue;
      }
      return std::nullopt;  // closed
    }
    if (c == '\n') {
      ++lines;
      const std::size_t end = text.find('\n', i + 1);
      const std::string_view line(text.data() + i + 1,
                                  (end == std::string::npos ? text.size() : end) - (i + 1));
      if (const auto key = key_of_line(line)) return RunawayQuote{lines, *key};
    }
  }
  return std::nullopt;
}

}  // namespace

std::string Field::as_string() const {
  const std::string allowed = "text (\"\" for an empty text)";
  if (is_null()) fail("has no value", allowed);
  if (!node_.IsScalar()) fail(describe_value() + " is not text", allowed);
  std::string value = node_.Scalar();
  // yaml-cpp folds a quoted text that runs over several lines into one: `name: "abc` followed
  // by `seed: 1` reads as the name "abc seed: 1 " and seed silently keeps its default
  if (text_ && node_.Mark().pos >= 0) {
    if (const auto r = runaway_quote(*text_, static_cast<std::size_t>(node_.Mark().pos))) {
      fail("is a quoted text whose closing quote is missing: it runs over " +
               std::to_string(r->line_offset) + " line" + (r->line_offset == 1 ? "" : "s") +
               " to '" + r->key + "' (line " + std::to_string(line_ + r->line_offset) +
               "), which reads like the next key",
           "text with its closing quote on the same line");
    }
  }
  if (const auto at = invalid_utf8_at(value)) {
    char byte[8];
    std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(value[*at]));
    fail("is not valid UTF-8 (byte " + std::string(byte) + " at byte " + std::to_string(*at) +
             " of the text)",
         "text in UTF-8");
  }
  return value;
}

std::string Field::scalar_for_name(std::string_view noun, const std::string& allowed) const {
  if (is_null()) fail("has no value", allowed);
  if (!node_.IsScalar())
    fail(describe_value() + " is not a " + std::string(noun) + " name", allowed);
  return node_.Scalar();
}

void Field::fail_name(std::string_view value, std::string_view noun, const std::string& allowed,
                      const std::vector<std::string>& names) const {
  fail(quote(value) + " is not a " + std::string(noun), allowed,
       closest_name(value, names).value_or(""));
}

// ---------------------------------------------------------------------------------------------
// Field: lists

void Field::expect_list(std::string_view allowed) const {
  if (is_null() || node_.IsSequence()) return;
  fail(describe_value() + " is not a list", std::string(allowed));
}

std::size_t Field::size() const {
  return is_list() ? node_.size() : 0;
}

Field Field::item(std::size_t i) const {
  const YAML::Node& self = node_;
  const YAML::Node value = self[i];
  std::shared_ptr<NodeState>* slot =
      state_ && i < state_->items.size() ? &state_->items[i] : nullptr;
  return make_child(path_ + "[" + std::to_string(i) + "]", value, node_.Mark(), true, slot);
}

}  // namespace sonarloop::config
