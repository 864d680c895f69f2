#pragma once
// Structured validation problems, returned by the validate() functions of sim's plain-data
// descriptions (vehicle_desc.h). Each problem names the field, its value and what is allowed, in
// SI units as sim uses them, so that a loader can say the same in its own terms (the YAML key,
// its line, degrees instead of radians) without restating the limits or parsing messages.
//
// Header only: no files, no sockets, no clock (docs/design.md, sim is pure).
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace sonarloop {

// "no bound" on either side of a Limit
inline constexpr double kNoBound = std::numeric_limits<double>::infinity();

// The allowed values of one number: an interval, open or closed at either end, in the SI unit
// `unit` ("" = dimensionless). Infinite bounds mean "no bound"; the value must be finite
// whatever the bounds. `integer`: whole numbers only (the field is an int).
struct Limit {
  double lo = -kNoBound;
  double hi = kNoBound;
  bool lo_open = false;
  bool hi_open = false;
  std::string_view unit;
  bool integer = false;

  static constexpr Limit finite(std::string_view unit = {}) {
    return {-kNoBound, kNoBound, false, false, unit, false};
  }
  static constexpr Limit closed(double lo, double hi, std::string_view unit = {}) {
    return {lo, hi, false, false, unit, false};
  }
  static constexpr Limit above(double lo, std::string_view unit = {}) {
    return {lo, kNoBound, true, false, unit, false};
  }
  static constexpr Limit at_least(double lo, std::string_view unit = {}) {
    return {lo, kNoBound, false, false, unit, false};
  }
  // (lo, hi]: positive up to a maximum
  static constexpr Limit above_up_to(double lo, double hi, std::string_view unit = {}) {
    return {lo, hi, true, false, unit, false};
  }
  static constexpr Limit open(double lo, double hi, std::string_view unit = {}) {
    return {lo, hi, true, true, unit, false};
  }
  static constexpr Limit whole(int lo, int hi) {
    return {static_cast<double>(lo), static_cast<double>(hi), false, false, {}, true};
  }

  bool bounded() const { return std::isfinite(lo) || std::isfinite(hi); }

  bool contains(double v) const {
    if (!std::isfinite(v)) return false;
    if (lo_open ? !(v > lo) : !(v >= lo)) return false;
    return hi_open ? v < hi : v <= hi;
  }

  // "(0, 20] m/s", "[1, 10000]", "(0, inf) m": interval notation, 6 significant digits
  std::string text() const {
    std::ostringstream os;
    os << (lo_open || !std::isfinite(lo) ? "(" : "[") << lo << ", " << hi
       << (hi_open || !std::isfinite(hi) ? ")" : "]");
    if (!unit.empty()) os << " " << unit;
    return os.str();
  }
};

// One violation found by a validate() function.
struct Problem {
  // The field's dotted path in the description, as the C++ names it, with the prefix the caller
  // gave: "trajectory.attitude.max_roll", "trajectory.waypoints[2]", "nav.noise_step_s".
  std::string field;
  std::optional<double> value;   // the field's value, SI; nullopt when not about one number
  std::optional<Limit> allowed;  // what the rule allows, SI; nullopt for a rule of another kind
  std::string text;              // the problem in words: "must be in (0, 1.5708) rad"

  // "trajectory.attitude.max_roll = 2: must be in (0, 1.5708) rad", "trajectory.waypoints: ..."
  std::string message() const {
    std::ostringstream os;
    os << field;
    if (value) os << " = " << *value;
    os << ": " << text;
    return os.str();
  }
};

// The problem of `value` outside `limit` (nullopt when it is inside), worded as validate() words
// it: "must be in [lo, hi] unit", or "must be a finite number (unit)" for an unbounded limit.
inline std::optional<Problem> check_limit(std::string field, double value, const Limit& limit) {
  if (limit.contains(value)) return std::nullopt;
  std::string text = limit.bounded() ? "must be in " + limit.text() : "must be a finite number";
  if (!limit.bounded() && !limit.unit.empty()) text += " (" + std::string(limit.unit) + ")";
  return Problem{std::move(field), value, limit, std::move(text)};
}

// Every problem's message, joined by "; " (for an exception's what()).
inline std::string join_messages(const std::vector<Problem>& problems) {
  std::string out;
  for (const Problem& p : problems) {
    if (!out.empty()) out += "; ";
    out += p.message();
  }
  return out;
}

}  // namespace sonarloop
