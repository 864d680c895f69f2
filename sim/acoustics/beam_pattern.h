#pragma once
// Beam pattern and directivity of a continuous, uniformly weighted line array
// (docs/physics.md §0, §4).
//
// Source: Urick, "Principles of Underwater Sound", 3rd ed. (1983) §3.6 and Table 3.1; Pailhas,
// Petillot & Capus (2010) use the same pattern (docs/physics.md §0):
//   B(θ) = sin(x)/x ,   x = (π·l/λ)·sin θ        one-way PRESSURE pattern, θ off broadside
// The two-way (transmit + receive with the same aperture) pressure pattern is B², i.e.
// 2 × 20·log10|B| in dB; intensity patterns are the squares of the pressure patterns.
//
// Validity: far field (r > l²/λ), uniform weighting, no element spacing effects (continuous
// aperture), l > λ for the beamwidth formulas.
#include <cmath>
#include <numbers>

namespace sonarloop::acoustics {

// x at which sin(x)/x = 1/√2 (one-way -3 dB); root of sin(x)/x - 2^-1/2, Urick Table 3.1.
inline constexpr double kSincHalfPowerX = 1.3915573782515103;
// x at which (sin(x)/x)² = 1/√2 (two-way -3 dB).
inline constexpr double kSincSquaredHalfPowerX = 1.0019063576966074;
// First sidelobe of sin(x)/x: root of tan x = x, level -13.2615 dB one-way.
inline constexpr double kSincFirstSidelobeX = 4.493409457909064;
// Floor for dB patterns, so that nulls give a finite number.
inline constexpr double kPatternFloorDb = -200.0;

// sin(x)/x, exact (= 1) at x = 0 and accurate near it. Pure, cheap, branch-light.
inline double sinc(double x) {
  // below 1e-4 the series 1 - x²/6 is exact to double precision (next term x⁴/120 < 1e-18)
  if (std::fabs(x) < 1e-4) return 1.0 - x * x / 6.0;
  return std::sin(x) / x;
}

// One-way pressure pattern B(θ) of a line array of length length_m at wavelength wavelength_m,
// θ = off_axis_rad measured from broadside in the plane containing the array. Signed: sidelobes
// alternate in sign. B(0) = 1.
double line_array_pattern(double off_axis_rad, double length_m, double wavelength_m);

// One-way pattern in dB, 20·log10|B|, floored at kPatternFloorDb.
double line_array_pattern_db(double off_axis_rad, double length_m, double wavelength_m);

// Two-way pattern in dB, 40·log10|B| (transmit and receive with the same array), floored at
// kPatternFloorDb.
double two_way_pattern_db(double off_axis_rad, double length_m, double wavelength_m);

// Directivity index of a line array, l >> λ: DI = 10·log10(2l/λ) dB (Urick Table 3.2).
double directivity_index_line_db(double length_m, double wavelength_m);

// Directivity index of a rectangular piston l × w in a baffle, l, w >> λ:
// DI = 10·log10(4π·l·w/λ²) dB (Urick Table 3.2).
double directivity_index_rect_db(double length_m, double width_m, double wavelength_m);

// Full -3 dB beamwidth of the one-way pattern: 2·asin(1.391557·λ/(π·l)) ≈ 0.8859·λ/l rad.
// Returns π when the aperture is too short for a -3 dB point to exist.
double beamwidth_3db_one_way_rad(double length_m, double wavelength_m);

// Full -3 dB beamwidth of the two-way pattern B²: 2·asin(1.001906·λ/(π·l)) ≈ 0.6378·λ/l rad.
double beamwidth_3db_two_way_rad(double length_m, double wavelength_m);

// Angle of the first null, sin θ = λ/l (π/2 if λ >= l).
double first_null_rad(double length_m, double wavelength_m);

// A sidescan transducer: a rectangular aperture, long along track, short vertically, tilted
// down by depression_rad (positive below horizontal) about the along-track axis.
struct SidescanArray {
  double length_m;        // along-track aperture (sets the horizontal beamwidth)
  double height_m;        // vertical aperture (sets the vertical beamwidth)
  double depression_rad;  // depression of the acoustic axis below horizontal
};

// Vertical off-axis angle of a ray whose depression below horizontal is ray_depression_rad.
inline double vertical_off_axis_rad(const SidescanArray& array, double ray_depression_rad) {
  return ray_depression_rad - array.depression_rad;
}

// Two-way INTENSITY pattern (linear, 1 on axis) of a separable rectangular aperture:
// per pass the intensity pattern is |B_h|²·|B_v|², and transmit + receive square it:
//   G = (B_h·B_v)⁴ ,  B_h = sinc(π·length/λ·sin ψ_along), B_v = sinc(π·height/λ·sin ψ_vert).
// along_angle_rad is the off-broadside angle in the horizontal (along-track) plane,
// vertical_angle_from_axis_rad the angle from the acoustic axis in the vertical plane (see
// vertical_off_axis_rad). Inline for the renderer's hot loop: two sines, no allocation.
inline double array_pattern_two_way(const SidescanArray& array, double wavelength_m,
                                    double along_angle_rad, double vertical_angle_from_axis_rad) {
  const double k_half = std::numbers::pi / wavelength_m;  // π/λ
  const double bh = sinc(k_half * array.length_m * std::sin(along_angle_rad));
  const double bv = sinc(k_half * array.height_m * std::sin(vertical_angle_from_axis_rad));
  const double p = bh * bv;  // one-way pressure
  const double p2 = p * p;   // one-way intensity = two-way pressure
  return p2 * p2;            // two-way intensity
}

}  // namespace sonarloop::acoustics
