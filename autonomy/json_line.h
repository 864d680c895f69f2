#pragma once
// A small reader for one-line JSON objects (JSON Lines: contact reports, the agent's records):
// the top-level members of an object, each as its raw text (a string already unescaped, a
// number, true/false/null, or the whole text of a nested object or array). Enough for the
// formats sonarloop writes with drivers/json/json_writer.h; not a general JSON library.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sonarloop::autonomy {

class JsonLine {
 public:
  // Parses `text` (one JSON object, surrounding whitespace allowed). nullopt with `error` set on
  // malformed input.
  static std::optional<JsonLine> parse(std::string_view text, std::string& error);

  bool has(const std::string& key) const { return members_.count(key) != 0; }
  // Present and not null.
  bool present(const std::string& key) const;
  std::optional<double> number(const std::string& key) const;
  std::optional<std::string> string(const std::string& key) const;
  std::optional<bool> boolean(const std::string& key) const;
  // A nested object's members.
  std::optional<JsonLine> object(const std::string& key) const;
  // The objects of a nested array of objects (other elements are skipped).
  std::vector<JsonLine> objects(const std::string& key) const;
  // Member names and raw texts, in key order.
  const std::map<std::string, std::string>& members() const { return members_; }

 private:
  std::map<std::string, std::string> members_;  // key -> raw text (strings unescaped, quoted)
};

}  // namespace sonarloop::autonomy
