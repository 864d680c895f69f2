#include "config/loader/yaml_fields.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <span>
#include <sstream>
#include <system_error>

#include <yaml-cpp/eventhandler.h>

namespace sonarloop::config {
namespace {

// longest value text quoted in a message before it is cut with "..."
constexpr std::size_t kMaxQuotedChars = 60;
// nesting shown when a list or map is printed in a message
constexpr int kMaxShownDepth = 3;

const std::string kFloatTag = "tag:yaml.org,2002:float";
const std::string kIntTag = "tag:yaml.org,2002:int";

// control characters (a block scalar's newlines) written as escapes: one issue, one line
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
  if (s.size() > kMaxQuotedChars) {
    return "'" + printable(s.substr(0, kMaxQuotedChars)) + "...'";
  }
  return "'" + printable(s) + "'";
}

std::string display_path(const std::string& path) {
  return path.empty() ? "(top level)" : path;
}

std::string child_path(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

// 1-based line/column of a mark, 0 when yaml-cpp has none
int mark_line(const YAML::Mark& m) {
  return m.is_null() || m.line < 0 ? 0 : m.line + 1;
}
int mark_column(const YAML::Mark& m) {
  return m.is_null() || m.column < 0 ? 0 : m.column + 1;
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

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

enum class NumberStatus { kOk, kNotANumber, kNonFinite, kOverflow };

// A YAML 1.2 core-schema decimal number: optional sign, digits, optional fraction and exponent.
// No hex, no underscores, no inf/nan (those are reported as non-finite).
NumberStatus parse_real(std::string_view s, double& out) {
  std::string_view body = s;
  if (!body.empty() && (body.front() == '+' || body.front() == '-')) body.remove_prefix(1);
  const std::string b = lower(body);
  if (b == ".inf" || b == ".nan" || b == "inf" || b == "nan" || b == "infinity") {
    return NumberStatus::kNonFinite;
  }
  if (body.empty() ||
      !(std::isdigit(static_cast<unsigned char>(body.front())) || body.front() == '.')) {
    return NumberStatus::kNotANumber;
  }
  // from_chars takes no '+', and a '-' only in front
  const std::string_view text = (!s.empty() && s.front() == '+') ? s.substr(1) : s;
  const auto res =
      std::from_chars(text.data(), text.data() + text.size(), out, std::chars_format::general);
  if (res.ptr != text.data() + text.size()) return NumberStatus::kNotANumber;
  if (res.ec == std::errc::result_out_of_range) return NumberStatus::kOverflow;
  if (res.ec != std::errc()) return NumberStatus::kNotANumber;
  if (!std::isfinite(out)) return NumberStatus::kNonFinite;
  return NumberStatus::kOk;
}

// optional sign and decimal digits; magnitude in `mag`
bool parse_integer(std::string_view s, bool& negative, std::uint64_t& mag, bool& overflow) {
  negative = false;
  overflow = false;
  if (!s.empty() && (s.front() == '+' || s.front() == '-')) {
    negative = s.front() == '-';
    s.remove_prefix(1);
  }
  if (s.empty()) return false;
  for (char c : s) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  }
  const auto res = std::from_chars(s.data(), s.data() + s.size(), mag);
  if (res.ec == std::errc::result_out_of_range) {
    overflow = true;
    return true;
  }
  return res.ec == std::errc() && res.ptr == s.data() + s.size();
}

std::string describe_ranges(std::span<const Range> ranges, std::string_view components) {
  std::string out =
      "a list [" + std::string(components) + "] of " + std::to_string(ranges.size()) + " numbers";
  const bool same = std::all_of(ranges.begin(), ranges.end(), [&](const Range& r) {
    return r.describe() == ranges.front().describe();
  });
  const Range& r0 = ranges.front();
  if (same && !std::isfinite(r0.lo) && !std::isfinite(r0.hi) && r0.note.empty()) {
    return "a list [" + std::string(components) + "] of " + std::to_string(ranges.size()) +
           " finite numbers";
  }
  if (same) return out + ", each " + r0.describe();
  // per component: "north -50 .. 50, east -50 .. 50"
  std::vector<std::string> names;
  std::string_view rest = components;
  while (!rest.empty()) {
    const auto comma = rest.find(',');
    std::string_view name = rest.substr(0, comma);
    while (!name.empty() && name.front() == ' ')
      name.remove_prefix(1);
    names.emplace_back(name);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  out += ": ";
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    if (i) out += "; ";
    out +=
        (i < names.size() ? names[i] : "[" + std::to_string(i) + "]") + " " + ranges[i].describe();
  }
  return out;
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
// Range

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

std::string Range::describe() const {
  const bool has_lo = std::isfinite(lo);
  const bool has_hi = std::isfinite(hi);
  std::string out;
  if (has_lo && has_hi && !lo_open && !hi_open) {
    out = format_number(lo) + " .. " + format_number(hi);
  } else if (has_lo && has_hi) {
    out = (lo_open ? "> " : ">= ") + format_number(lo) + " and " + (hi_open ? "< " : "<= ") +
          format_number(hi);
  } else if (has_lo) {
    out = (lo_open ? "> " : ">= ") + format_number(lo);
  } else if (has_hi) {
    out = (hi_open ? "< " : "<= ") + format_number(hi);
  } else {
    out = "any finite number";
  }
  if (!note.empty()) out += " (" + note + ")";
  return out;
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
// Field: typed getters

void Field::check_default(double def, const Range& range) const {
  if (!range.contains(def)) {
    fail("is not set, and its default " + format_number(def) + " is out of range (set it)",
         range.describe());
  }
}

double Field::get_double(std::string_view key, double def, const Range& range) const {
  const Field f = child(key);
  if (!f.present()) {
    f.check_default(def, range);
    return def;
  }
  return f.as_double(range);
}

int Field::get_int(std::string_view key, int def, int lo, int hi) const {
  const Field f = child(key);
  return f.present() ? f.as_int(lo, hi) : def;
}

std::uint64_t Field::get_uint64(std::string_view key, std::uint64_t def, std::uint64_t lo,
                                std::uint64_t hi) const {
  const Field f = child(key);
  return f.present() ? f.as_uint64(lo, hi) : def;
}

bool Field::get_bool(std::string_view key, bool def) const {
  const Field f = child(key);
  return f.present() ? f.as_bool() : def;
}

std::string Field::get_string(std::string_view key, const std::string& def) const {
  const Field f = child(key);
  return f.present() ? f.as_string() : def;
}

Vec2 Field::get_vec2(std::string_view key, const Vec2& def, const Range& each,
                     std::string_view components) const {
  return get_vec2(key, def, std::array<Range, 2>{each, each}, components);
}

Vec2 Field::get_vec2(std::string_view key, const Vec2& def, const std::array<Range, 2>& ranges,
                     std::string_view components) const {
  const Field f = child(key);
  if (f.present()) return f.as_vec2(ranges, components);
  if (!ranges[0].contains(def.x()) || !ranges[1].contains(def.y())) {
    f.fail("is not set, and its default [" + format_number(def.x()) + ", " +
               format_number(def.y()) + "] is out of range (set it)",
           describe_ranges(ranges, components));
  }
  return def;
}

Vec3 Field::get_vec3(std::string_view key, const Vec3& def, const Range& each,
                     std::string_view components) const {
  const Field f = child(key);
  if (f.present()) return f.as_vec3({each, each, each}, components);
  if (!each.contains(def.x()) || !each.contains(def.y()) || !each.contains(def.z())) {
    f.fail("is not set, and its default is out of range (set it)",
           describe_ranges(std::array<Range, 3>{each, each, each}, components));
  }
  return def;
}

// ---------------------------------------------------------------------------------------------
// Field: this node as a value

double Field::as_double(const Range& range) const {
  const bool unbounded = !std::isfinite(range.lo) && !std::isfinite(range.hi);
  const std::string allowed = unbounded ? range.describe() : "a number " + range.describe();
  if (is_null()) fail("has no value", allowed);
  if (!node_.IsScalar()) fail(describe_value() + " is not a number", allowed);
  const std::string& text = node_.Scalar();
  const std::string& tag = node_.Tag();
  if (tag == "!") fail(quote(text) + " is a quoted string, not a number", allowed);
  if (tag != "?" && tag != kFloatTag && tag != kIntTag) {
    fail(quote(text) + " is tagged " + tag + ", not a number", allowed);
  }
  double v = 0.0;
  switch (parse_real(text, v)) {
    case NumberStatus::kOk:
      break;
    case NumberStatus::kNonFinite:
      fail(quote(text) + " is not a finite number", allowed);
    case NumberStatus::kOverflow:
      fail(quote(text) + " is beyond the range of a double", allowed);
    case NumberStatus::kNotANumber:
      fail(quote(text) + " is not a number", allowed);
  }
  if (!range.contains(v)) fail(text + " is out of range", range.describe());
  return v;
}

namespace {
std::string int_allowed(std::string_view lo, std::string_view hi, bool unbounded_hi) {
  return unbounded_hi ? "an integer >= " + std::string(lo)
                      : "an integer " + std::string(lo) + " .. " + std::string(hi);
}
}  // namespace

std::uint64_t Field::as_uint64(std::uint64_t lo, std::uint64_t hi) const {
  const std::string allowed = int_allowed(std::to_string(lo), std::to_string(hi),
                                          hi == std::numeric_limits<std::uint64_t>::max());
  if (is_null()) fail("has no value", allowed);
  if (!node_.IsScalar()) fail(describe_value() + " is not an integer", allowed);
  const std::string& text = node_.Scalar();
  if (node_.Tag() == "!") fail(quote(text) + " is a quoted string, not an integer", allowed);
  if (node_.Tag() != "?" && node_.Tag() != kIntTag) {
    fail(quote(text) + " is tagged " + node_.Tag() + ", not an integer", allowed);
  }
  bool negative = false;
  bool overflow = false;
  std::uint64_t mag = 0;
  if (!parse_integer(text, negative, mag, overflow)) {
    fail(quote(text) + " is not an integer", allowed);
  }
  if (overflow || (negative && mag != 0) || mag < lo || mag > hi) {
    fail(text + " is out of range", allowed);
  }
  return mag;
}

int Field::as_int(int lo, int hi) const {
  const std::string allowed =
      int_allowed(std::to_string(lo), std::to_string(hi), hi == std::numeric_limits<int>::max());
  if (is_null()) fail("has no value", allowed);
  if (!node_.IsScalar()) fail(describe_value() + " is not an integer", allowed);
  const std::string& text = node_.Scalar();
  if (node_.Tag() == "!") fail(quote(text) + " is a quoted string, not an integer", allowed);
  if (node_.Tag() != "?" && node_.Tag() != kIntTag) {
    fail(quote(text) + " is tagged " + node_.Tag() + ", not an integer", allowed);
  }
  bool negative = false;
  bool overflow = false;
  std::uint64_t mag = 0;
  if (!parse_integer(text, negative, mag, overflow)) {
    fail(quote(text) + " is not an integer", allowed);
  }
  // |int| fits comfortably in 2^32; anything larger is out of range whatever lo and hi are
  constexpr std::uint64_t kLimit = std::uint64_t{1} << 32;
  if (overflow || mag >= kLimit) fail(text + " is out of range", allowed);
  const std::int64_t v =
      negative ? -static_cast<std::int64_t>(mag) : static_cast<std::int64_t>(mag);
  if (v < lo || v > hi) fail(text + " is out of range", allowed);
  return static_cast<int>(v);
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

namespace {
template <std::size_t N>
std::array<double, N> vector_of(const Field& f, const std::array<Range, N>& ranges,
                                std::string_view components) {
  const std::string allowed = describe_ranges(ranges, components);
  if (f.is_null()) f.fail("has no value", allowed);
  if (f.is_scalar()) f.fail(f.describe_value() + " is a single value, not a list", allowed);
  if (!f.is_list()) f.fail(f.describe_value() + " is not a list", allowed);
  if (f.size() != N) {
    f.fail(f.describe_value() + " has " + std::to_string(f.size()) +
               (f.size() == 1 ? " value" : " values") + ", not " + std::to_string(N),
           allowed);
  }
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i)
    out[i] = f.item(i).as_double(ranges[i]);
  return out;
}
}  // namespace

Vec2 Field::as_vec2(const std::array<Range, 2>& ranges, std::string_view components) const {
  const auto v = vector_of<2>(*this, ranges, components);
  return {v[0], v[1]};
}

Vec3 Field::as_vec3(const std::array<Range, 3>& ranges, std::string_view components) const {
  const auto v = vector_of<3>(*this, ranges, components);
  return {v[0], v[1], v[2]};
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

// ---------------------------------------------------------------------------------------------
// Free functions

std::string read_text_file(const std::string& path) {
  namespace fs = std::filesystem;
  const auto fail = [&](const std::string& problem) {
    throw ConfigError(ConfigIssue{path, "(file)", problem, "a readable YAML file", {}, 0, 0});
  };
  std::error_code ec;
  const auto st = fs::status(path, ec);
  if (!fs::exists(st)) fail("no such file");
  if (fs::is_directory(st)) fail("is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(std::string("cannot be opened: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) fail("cannot be read");
  return ss.str();
}

namespace {

// Notes where each document starts; builds nothing.
class DocumentStarts : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark& mark) override { marks.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}

  std::vector<YAML::Mark> marks;
};

ConfigIssue syntax_issue(const std::string& file, const std::string& problem,
                         const YAML::Mark& mark) {
  return {file,
          "",
          "YAML syntax error: " + problem,
          "well-formed YAML (see config/reference.yaml)",
          {},
          mark_line(mark),
          mark_column(mark)};
}

}  // namespace

Field parse_document(const std::string& yaml_text, const std::string& file) {
  try {
    // Count the documents first, stopping at the second. Not YAML::LoadAll: in yaml-cpp 0.7 a
    // token no document can start with (a ',' at the top level) makes LoadAll loop for ever,
    // adding empty documents until memory runs out (yaml-cpp issue #1040, fixed upstream by
    // PR #1319). Here such a token shows as a second document starting where the first did.
    std::istringstream in(yaml_text);
    YAML::Parser parser(in);
    DocumentStarts starts;
    while (starts.marks.size() < 2 && parser.HandleNextDocument(starts)) {
    }
    if (starts.marks.size() == 2) {
      const YAML::Mark& m = starts.marks[1];
      if (m.pos == starts.marks[0].pos) {
        const auto pos = static_cast<std::size_t>(std::max(m.pos, 0));
        const std::string what =
            pos < yaml_text.size() ? quote(yaml_text.substr(pos, 1)) : std::string("input");
        throw ConfigError(syntax_issue(file, "unexpected " + what, m));
      }
      throw ConfigError(ConfigIssue{file,
                                    "",
                                    "holds more than one YAML document",
                                    "a single document",
                                    {},
                                    mark_line(m),
                                    mark_column(m)});
    }
    const YAML::Node root = YAML::Load(yaml_text);
    return Field(root.IsDefined() ? root : YAML::Node(YAML::NodeType::Null), file,
                 std::make_shared<const std::string>(yaml_text));
  } catch (const YAML::Exception& e) {
    throw ConfigError(syntax_issue(file, e.msg, e.mark));
  }
}

std::string format_number(double v) {
  // plain digits for everyday magnitudes ("100000", "0.025"), exponent form beyond them;
  // either way the shortest text that reads back as the same double
  char buf[400];
  const double a = std::fabs(v);
  const bool plain = a == 0.0 || (a >= 1e-4 && a < 1e15);
  const auto res = plain ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed)
                         : std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific);
  return std::string(buf, res.ptr);
}

std::size_t edit_distance(std::string_view a_in, std::string_view b_in) {
  const std::string a = lower(a_in);
  const std::string b = lower(b_in);
  const std::size_t n = a.size();
  const std::size_t m = b.size();
  // three rows of the optimal-string-alignment table
  std::vector<std::size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (std::size_t j = 0; j <= m; ++j)
    prev[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        cur[j] = std::min(cur[j], prev2[j - 2] + 1);
      }
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
  }
  return prev[m];
}

std::optional<std::string> closest_name(std::string_view word,
                                        const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  std::size_t best_d = std::numeric_limits<std::size_t>::max();
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    const std::size_t limit = std::max<std::size_t>(1, c.size() / 3);
    if (d <= limit && d < best_d) {
      best = c;
      best_d = d;
    }
  }
  return best;
}

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

}  // namespace sonarloop::config
