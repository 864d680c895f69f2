#pragma once
// A small streaming JSON writer (RFC 8259): objects, arrays, strings with escaping, numbers,
// booleans and null, with commas and nesting handled. Non-finite numbers are written as null
// (JSON has no NaN). Used for truth files, bench lines and contact reports.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sonarloop::json {

class Writer {
 public:
  // pretty: newlines and two-space indentation; otherwise one compact line.
  explicit Writer(bool pretty = false) : pretty_(pretty) {}

  Writer& begin_object();
  Writer& end_object();
  Writer& begin_array();
  Writer& end_array();
  Writer& key(std::string_view k);

  Writer& value(std::string_view s);
  Writer& value(const char* s) { return value(std::string_view(s)); }
  Writer& value(double v, int significant_digits = 10);
  Writer& value(std::int64_t v);
  Writer& value(int v) { return value(static_cast<std::int64_t>(v)); }
  Writer& value(std::uint64_t v);
  Writer& value(bool v);
  Writer& null();

  // key + value in one call
  template <class T>
  Writer& field(std::string_view k, const T& v) {
    key(k);
    return value(v);
  }
  Writer& field(std::string_view k, double v, int significant_digits) {
    key(k);
    return value(v, significant_digits);
  }

  const std::string& str() const { return out_; }

 private:
  void before_value();
  void newline();

  bool pretty_;
  std::string out_;
  struct Level {
    bool is_object;
    bool empty;
  };
  std::vector<Level> stack_;
  bool after_key_ = false;
};

// `s` as a JSON string literal, with quotes.
std::string quote(std::string_view s);

}  // namespace sonarloop::json
