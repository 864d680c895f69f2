#pragma once
// A small validation toolkit over yaml-cpp, shared by every config loader (scene, sonar,
// vehicle, ...). docs/design.md, "Rules of the house": bad input gets a clear error naming the
// file, the key and what is allowed.
//
// A Field wraps one YAML node together with the file it came from and its key path
// ("seabed.regions[1].texture.ripples.wavelength_m"). Loaders read a map with typed getters that
// take a default and an allowed range; every key a getter asks for is recorded as known, and
// finish() then rejects the keys of the map that nobody asked for, with a "did you mean"
// suggestion when a known key is close by edit distance.
//
// Conventions (the same for every loader):
// - A missing key takes its default. The default is checked against the allowed range too,
//   because cross-field ranges (e.g. "inner_scale_m >= spacing_m") can exclude it.
// - A key with no value (`key:`, `key: ~`, `key: null`) is an empty map or an empty list where a
//   map or a list is expected, and an error where a single value is expected.
// - Numbers must be plain (unquoted) decimal YAML scalars and finite: .nan, .inf, 1e999 and
//   "30" (quoted) are rejected. Integers take no fraction or exponent. Booleans are true/false.
// - Duplicate keys in one map are errors (yaml-cpp would silently keep both).
//
// Failure: every problem throws ConfigError, whose message always reads
//   <file>: <key.path>: <problem> (line L, column C); allowed: <what is allowed>
// with " (did you mean 'x'?)" appended when there is a close match. The line and column (1-based)
// appear whenever yaml-cpp knows where the node is. The problem quotes the bad value.
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "sim/frames.h"

namespace sonarloop::config {

// One problem found in a configuration source.
struct ConfigIssue {
  std::string file;        // file name as given, or a source name such as "<default scenario>"
  std::string path;        // key path; "" = the whole document
  std::string problem;     // what is wrong, quoting the bad value
  std::string allowed;     // what would be accepted
  std::string suggestion;  // closest accepted name, "" if none is close
  int line = 0;            // 1-based; 0 = unknown
  int column = 0;          // 1-based; 0 = unknown

  // "<file>: <path>: <problem> (line L, column C); allowed: <allowed> (did you mean 'x'?)"
  std::string message() const;
};

// Thrown for every configuration problem. what() is the message of each issue, one per line.
class ConfigError : public std::runtime_error {
 public:
  explicit ConfigError(ConfigIssue issue);
  explicit ConfigError(std::vector<ConfigIssue> issues);  // at least one

  const std::vector<ConfigIssue>& issues() const { return issues_; }
  const ConfigIssue& first() const { return issues_.front(); }

 private:
  std::vector<ConfigIssue> issues_;
};

// An allowed interval of real numbers, optionally open at either end, with an optional note
// that explains where a bound comes from ("at least seabed.grid_spacing_m").
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;
  std::string note;

  static Range closed(double lo, double hi) { return {lo, hi, false, false, {}}; }
  static Range at_least(double lo) { return closed(lo, std::numeric_limits<double>::infinity()); }
  static Range above(double lo) {
    return {lo, std::numeric_limits<double>::infinity(), true, false, {}};
  }
  static Range any() { return {}; }
  Range with_note(std::string n) const {
    Range r = *this;
    r.note = std::move(n);
    return r;
  }

  bool contains(double v) const;
  // "0.05 .. 20", ">= 1", "> 1 and <= 10000", "any finite number"; then " (note)".
  std::string describe() const;
};

// Names accepted for an enumerated value, e.g. sediments, target types.
template <class T>
struct NameTable {
  std::string noun;                // "'x' is not a <noun>"
  std::string allowed;             // text of the allowed list for messages
  std::vector<std::string> names;  // every accepted spelling, offered as suggestions
  std::function<std::optional<T>(std::string_view)> find;
};

// One YAML node with its source file and key path. Cheap to copy. Every Field that visits the
// same map (a copy, or child("x") called twice) shares the record of which keys were asked for,
// so any of them may be finished.
class Field {
 public:
  // The root of a document (its path is empty). A null node stands for an empty map. `text`
  // (optional): the document's source, for checks yaml-cpp cannot make (an unclosed quote).
  Field(YAML::Node node, std::string file, std::shared_ptr<const std::string> text = nullptr);
  // Copies share the node (and the record of read keys). Assignment is deleted: yaml-cpp's
  // Node::operator= rebinds the node INSIDE the document, so `f = f.child("x")` would silently
  // rewrite the parsed tree.
  Field(const Field&) = default;
  Field(Field&&) = default;
  Field& operator=(const Field&) = delete;
  Field& operator=(Field&&) = delete;

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  const YAML::Node& node() const { return node_; }
  int line() const { return line_; }      // 1-based, 0 = unknown
  int column() const { return column_; }  // 1-based, 0 = unknown

  bool present() const { return present_; }  // false for a key that is not in its map
  bool is_null() const;                      // absent, or present with no value
  bool is_map() const;
  bool is_list() const;
  bool is_scalar() const;

  // How the value reads in a message: "'abc'", "a list [1, 2]", "a map {a: 1}", "empty".
  std::string describe_value() const;

  // --- maps (an absent or null node is an empty map) ---
  void expect_map(std::string_view allowed = "a map of 'key: value' lines") const;
  // Declares keys as known without reading them (fixes their order in "allowed" lists).
  void declare(std::initializer_list<std::string_view> keys) const;
  bool has(std::string_view key) const;     // declares `key` as known; true if it is in the map
  Field child(std::string_view key) const;  // declared as known; !present() if missing
  // Unknown keys of this map (never declared) -> ConfigError listing all of them.
  void finish() const;

  // Typed getters: the value of `key`, or `def` when the key is missing.
  double get_double(std::string_view key, double def, const Range& range) const;
  int get_int(std::string_view key, int def, int lo, int hi) const;
  std::uint64_t get_uint64(std::string_view key, std::uint64_t def, std::uint64_t lo = 0,
                           std::uint64_t hi = std::numeric_limits<std::uint64_t>::max()) const;
  bool get_bool(std::string_view key, bool def) const;
  std::string get_string(std::string_view key, const std::string& def) const;
  template <class T>
  T get_enum(std::string_view key, T def, const NameTable<T>& table) const;
  // [a, b] / [a, b, c]; `components` names them for messages, e.g. "north, east".
  Vec2 get_vec2(std::string_view key, const Vec2& def, const Range& each,
                std::string_view components) const;
  Vec2 get_vec2(std::string_view key, const Vec2& def, const std::array<Range, 2>& ranges,
                std::string_view components) const;
  Vec3 get_vec3(std::string_view key, const Vec3& def, const Range& each,
                std::string_view components) const;

  // --- this node as a value ---
  double as_double(const Range& range) const;
  // A finite number, its range not checked: for a value a later check judges (a description's
  // validate()). `described` is what "allowed" says when the value is not a number at all.
  double as_number(const Range& described) const;
  int as_int(int lo, int hi) const;
  std::uint64_t as_uint64(std::uint64_t lo, std::uint64_t hi) const;
  bool as_bool() const;
  // Text: valid UTF-8 only; a quoted text whose closing quote is missing, so that it runs over
  // a following line reading like a key ("name: \"abc" then "seed: 1"), is an error.
  std::string as_string() const;
  template <class T>
  T as_enum(const NameTable<T>& table) const;
  Vec2 as_vec2(const std::array<Range, 2>& ranges, std::string_view components) const;
  Vec3 as_vec3(const std::array<Range, 3>& ranges, std::string_view components) const;

  // --- lists (an absent or null node is an empty list) ---
  void expect_list(std::string_view allowed) const;
  std::size_t size() const;
  Field item(std::size_t i) const;

  // Throws ConfigError for this field: its file, path and line, the problem and what is allowed.
  [[noreturn]] void fail(std::string problem, std::string allowed,
                         std::string suggestion = {}) const;
  ConfigIssue issue(std::string problem, std::string allowed, std::string suggestion = {}) const;

 private:
  struct NodeState;
  struct MapEntry {
    std::string key;
    YAML::Node key_node;
    YAML::Node value;
    std::shared_ptr<NodeState> value_state;  // made when the value is first visited
  };
  // What is known about one map or list node; shared by every Field that visits the node, so
  // child("x") may be called more than once and each result finished.
  struct NodeState {
    std::vector<MapEntry> entries;                  // maps: in file order
    std::vector<std::string> declared;              // maps: keys asked for, in order
    std::vector<std::shared_ptr<NodeState>> items;  // lists: one slot per item
  };

  Field() = default;
  // `slot` keeps the child's state between visits (nullptr: a throwaway Field for a message)
  Field make_child(std::string path, YAML::Node value, const YAML::Mark& fallback, bool present,
                   std::shared_ptr<NodeState>* slot) const;
  MapEntry* find_entry(std::string_view key) const;
  // for a map or list node: takes the state in *slot, or makes it (indexing a map's keys)
  void attach_state(std::shared_ptr<NodeState>* slot);
  [[noreturn]] void fail_name(std::string_view value, std::string_view noun,
                              const std::string& allowed,
                              const std::vector<std::string>& names) const;
  std::string scalar_for_name(std::string_view noun, const std::string& allowed) const;
  // An integer scalar's text and magnitude (as_int, as_uint64); fails for anything that is not
  // one, with `allowed` as the message's "allowed" part.
  struct IntegerText {
    std::string text;
    bool negative = false;
    bool overflow = false;
    std::uint64_t magnitude = 0;
  };
  IntegerText integer_scalar(const std::string& allowed) const;
  void check_default(double def, const Range& range) const;

  YAML::Node node_;
  std::string file_;
  std::string path_;
  int line_ = 0;
  int column_ = 0;
  bool present_ = true;
  std::shared_ptr<NodeState> state_;         // maps and lists only
  std::shared_ptr<const std::string> text_;  // the document's source (may be null)
};

// The largest scenario or configuration file read: 64 MB (a list of 100,000 targets, one line
// each, is about 6 MB).
inline constexpr std::uintmax_t kMaxYamlFileBytes = std::uintmax_t{64} << 20;
// Reads a whole text file; a missing, unreadable, oversized or not regular file (a FIFO, a
// device) -> ConfigError naming the path.
std::string read_text_file(const std::string& path);

// Parses YAML text holding one document (empty text = an empty map) into its root Field.
// Syntax errors -> ConfigError with the line and column of the problem.
Field parse_document(const std::string& yaml_text, const std::string& file);

// Runs fn() (a parse of `source_name`) and turns a yaml-cpp exception into a ConfigError naming
// the source. yaml-cpp exceptions are not expected (the toolkit checks node kinds first); kept so
// that a yaml-cpp surprise still reaches the user as a configuration error.
template <class Fn>
auto with_yaml_errors(const std::string& source_name, Fn&& fn) {
  try {
    return fn();
  } catch (const YAML::Exception& e) {
    throw ConfigError(ConfigIssue{source_name,
                                  "",
                                  "YAML error: " + e.msg,
                                  "well-formed YAML",
                                  {},
                                  e.mark.is_null() ? 0 : e.mark.line + 1,
                                  e.mark.is_null() ? 0 : e.mark.column + 1});
  }
}

// Shortest text that reads back as the same double ("0.025", "1e+12").
std::string format_number(double v);

// Appends the YAML line "<pad><key>: <value>" ("<pad><key>:" for an empty value, a map's key)
// to out: the loaders' printers of what they read.
void append_yaml_line(std::string& out, std::string_view pad, std::string_view key,
                      std::string_view value);

// Optimal-string-alignment edit distance (insertions, deletions, substitutions, swaps of two
// adjacent characters), case-insensitive.
std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate closest to `word` if it is close enough to be a likely typo
// (distance <= max(1, length / 3)); ties go to the earlier candidate.
std::optional<std::string> closest_name(std::string_view word,
                                        const std::vector<std::string>& candidates);

// "a, b, c"
std::string join_names(const std::vector<std::string>& names);

// --- template definitions ---

template <class T>
T Field::as_enum(const NameTable<T>& table) const {
  const std::string text = scalar_for_name(table.noun, table.allowed);
  if (auto v = table.find(text)) return *v;
  fail_name(text, table.noun, table.allowed, table.names);
}

template <class T>
T Field::get_enum(std::string_view key, T def, const NameTable<T>& table) const {
  const Field f = child(key);
  return f.present() ? f.as_enum(table) : def;
}

}  // namespace sonarloop::config
