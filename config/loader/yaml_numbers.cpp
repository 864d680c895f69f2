// Numbers in YAML (yaml_fields.h): plain decimal scalars, ranges, the typed number getters, and
// the shortest text of a double.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <span>
#include <system_error>

#include "config/loader/yaml_fields.h"
#include "config/loader/yaml_text.h"

namespace sonarloop::config {
namespace {

using yaml_text::lower;
using yaml_text::quote;

const std::string kFloatTag = "tag:yaml.org,2002:float";
const std::string kIntTag = "tag:yaml.org,2002:int";

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
    // appended piece by piece: GCC 12 at -O3 warns falsely (-Wrestrict) on "[" + std::string
    if (i < names.size()) {
      out += names[i];
    } else {
      out += "[";
      out += std::to_string(i);
      out += "]";
    }
    out += " ";
    out += ranges[i].describe();
  }
  return out;
}

}  // namespace

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
// Field: numbers

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

double Field::as_number(const Range& described) const {
  const bool unbounded = !std::isfinite(described.lo) && !std::isfinite(described.hi);
  const std::string allowed = unbounded ? described.describe() : "a number " + described.describe();
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
  return v;
}

double Field::as_double(const Range& range) const {
  const double v = as_number(range);
  if (!range.contains(v)) fail(node_.Scalar() + " is out of range", range.describe());
  return v;
}

namespace {
std::string int_allowed(std::string_view lo, std::string_view hi, bool unbounded_hi) {
  return unbounded_hi ? "an integer >= " + std::string(lo)
                      : "an integer " + std::string(lo) + " .. " + std::string(hi);
}
}  // namespace

Field::IntegerText Field::integer_scalar(const std::string& allowed) const {
  if (is_null()) fail("has no value", allowed);
  if (!node_.IsScalar()) fail(describe_value() + " is not an integer", allowed);
  IntegerText r;
  r.text = node_.Scalar();
  if (node_.Tag() == "!") fail(quote(r.text) + " is a quoted string, not an integer", allowed);
  if (node_.Tag() != "?" && node_.Tag() != kIntTag) {
    fail(quote(r.text) + " is tagged " + node_.Tag() + ", not an integer", allowed);
  }
  if (!parse_integer(r.text, r.negative, r.magnitude, r.overflow)) {
    fail(quote(r.text) + " is not an integer", allowed);
  }
  return r;
}

std::uint64_t Field::as_uint64(std::uint64_t lo, std::uint64_t hi) const {
  const std::string allowed = int_allowed(std::to_string(lo), std::to_string(hi),
                                          hi == std::numeric_limits<std::uint64_t>::max());
  const auto [text, negative, overflow, mag] = integer_scalar(allowed);
  if (overflow || (negative && mag != 0) || mag < lo || mag > hi) {
    fail(text + " is out of range", allowed);
  }
  return mag;
}

int Field::as_int(int lo, int hi) const {
  const std::string allowed =
      int_allowed(std::to_string(lo), std::to_string(hi), hi == std::numeric_limits<int>::max());
  const auto [text, negative, overflow, mag] = integer_scalar(allowed);
  // |int| fits comfortably in 2^32; anything larger is out of range whatever lo and hi are
  constexpr std::uint64_t kLimit = std::uint64_t{1} << 32;
  if (overflow || mag >= kLimit) fail(text + " is out of range", allowed);
  const std::int64_t v =
      negative ? -static_cast<std::int64_t>(mag) : static_cast<std::int64_t>(mag);
  if (v < lo || v > hi) fail(text + " is out of range", allowed);
  return static_cast<int>(v);
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

void append_yaml_line(std::string& out, std::string_view pad, std::string_view key,
                      std::string_view value) {
  out += pad;
  out += key;
  out += ":";
  if (!value.empty()) {
    out += " ";
    out += value;
  }
  out += "\n";
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

}  // namespace sonarloop::config
