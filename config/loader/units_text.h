#pragma once
// YAML units and numbers in messages, shared by the loaders (sonar_loader, vehicle_loader).
//
// YAML keys carry friendly units in their names (heading_deg, frequency_khz, bin_size_cm, ...);
// the descriptions in sim/ hold SI units and radians (docs/design.md, "Units are SI in code").
// Each conversion is one correctly rounded multiplication or division, so a YAML value that is
// exact in binary (an integer, 7.5, ...) converts to the double nearest its decimal SI value
// (5 cm -> 0.05 m, 80 us -> 80e-6 s) and 180 degrees -> π, 90 -> π/2 (units/angles.h).
#include <string>

#include "config/loader/yaml_fields.h"
#include "sim/core/validation.h"

namespace sonarloop::config {

// The unit a YAML key is written in; kSi = the SI unit of the description's field.
enum class YamlUnit { kSi, kDegree, kKilohertz, kMicrosecond, kCentimetre };

double to_si(double yaml_value, YamlUnit unit);
double from_si(double si_value, YamlUnit unit);

// The shortest decimal number, in `unit`, that converts back to exactly `si` (7 for 0.07 m in
// cm, where 0.07 * 100 = 7.000000000000001; 90 for π/2 in degrees); the plain conversion when
// no decimal does.
double yaml_value(double si, YamlUnit unit);
// yaml_value as text, as format_number writes it.
std::string unit_text(double si, YamlUnit unit);

// A derived value for a message: 6 significant digits ("1.01456e+08").
std::string approx(double v);

// An SI limit of sim (sim/core/validation.h) as a YAML range in `unit`, for an "allowed" text:
// each bound the shortest decimal that converts back to it exactly, so "> 0 and < 90" for
// (0, π/2) rad in degrees. A bound that has no short decimal in `unit` (2 rad/s is
// 114.59155902616465 deg/s) is also given in SI in the note: "(2 rad/s)". `note` comes after.
Range yaml_range(const Limit& si, YamlUnit unit, const std::string& note = {});

}  // namespace sonarloop::config
