#include "config/loader/units_text.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "units/angles.h"

namespace sonarloop::config {
namespace {

// A bound whose shortest text in YAML units is longer than this is also given in SI.
constexpr std::size_t kMaxShortBoundChars = 10;

}  // namespace

double to_si(double yaml_value, YamlUnit unit) {
  switch (unit) {
    case YamlUnit::kSi:
      return yaml_value;
    case YamlUnit::kDegree:
      return yaml_value * kRadPerDeg;
    case YamlUnit::kKilohertz:
      return yaml_value * 1e3;
    case YamlUnit::kMicrosecond:
      return yaml_value / 1e6;
    case YamlUnit::kCentimetre:
      return yaml_value / 1e2;
  }
  return yaml_value;
}

double from_si(double si_value, YamlUnit unit) {
  switch (unit) {
    case YamlUnit::kSi:
      return si_value;
    case YamlUnit::kDegree:
      return si_value / kRadPerDeg;
    case YamlUnit::kKilohertz:
      return si_value / 1e3;
    case YamlUnit::kMicrosecond:
      return si_value * 1e6;
    case YamlUnit::kCentimetre:
      return si_value * 1e2;
  }
  return si_value;
}

double yaml_value(double si, YamlUnit unit) {
  const double v = from_si(si, unit);
  if (unit == YamlUnit::kSi || !std::isfinite(v)) return v;
  for (int digits = 1; digits <= 17; ++digits) {
    char buf[40];
    const auto printed =
        std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, digits);
    double candidate = 0.0;
    std::from_chars(buf, printed.ptr, candidate);
    if (to_si(candidate, unit) == si) return candidate;
  }
  return v;
}

std::string unit_text(double si, YamlUnit unit) {
  return format_number(yaml_value(si, unit));
}

std::string approx(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

Range yaml_range(const Limit& si, YamlUnit unit, const std::string& note) {
  Range r{yaml_value(si.lo, unit), yaml_value(si.hi, unit), si.lo_open, si.hi_open, {}};
  // the SI text of the bounds with no short decimal in `unit` (appended piece by piece: GCC 12
  // at -O3 warns falsely, -Wrestrict, on " " + std::string)
  std::string all;
  for (double bound : {si.lo, si.hi}) {
    if (unit == YamlUnit::kSi || !std::isfinite(bound)) continue;
    if (unit_text(bound, unit).size() <= kMaxShortBoundChars) continue;
    if (!all.empty()) all += ", ";
    all += format_number(bound);
    if (!si.unit.empty()) all.append(" ").append(si.unit);
  }
  if (!note.empty()) {
    if (!all.empty()) all += "; ";
    all += note;
  }
  return r.with_note(all);
}

}  // namespace sonarloop::config
