#pragma once
// Time-varied gain: the receiver gain that removes the range dependence of the echo.
//
//   TVG(r) = n·log10 r + 2·α·r       dB, r slant range in m, α in dB/m
// Source: docs/physics.md §3 (textbook rule, marked [M] there: no primary source was verified). The
// exponents follow from this library's sonar equation: a point target's echo falls as r⁻⁴
// (two-way spherical spreading, tests/sim/acoustics/oracles/spreading.h), so n = 40; a seabed
// cell's echo as A/r⁴ with A ∝ r (tests/sim/acoustics/oracles/reverberation.h), so n = 30; n = 20
// is the curve many commercial systems apply before a user-defined correction. Validity: as
// spherical spreading (far field, straight rays).
namespace sonarloop::acoustics {

// Spreading coefficients n of the TVG law.
inline constexpr double kTvgAreaCoeff = 30.0;       // seabed (area) returns
inline constexpr double kTvgPointCoeff = 40.0;      // point targets
inline constexpr double kTvgSphericalCoeff = 20.0;  // 20 log r + 2αr ("spherical")

enum class TvgLaw { kArea, kPoint, kSpherical };

// n·log10(r) + 2·α·r dB. range_m > 0.
double tvg_db(double range_m, double alpha_db_per_m, double spreading_coeff);

// The same with the coefficient of a named law.
double tvg_db(double range_m, double alpha_db_per_m, TvgLaw law);

// The spreading coefficient of a law (30, 40 or 20).
double tvg_spreading_coeff(TvgLaw law);

}  // namespace sonarloop::acoustics
