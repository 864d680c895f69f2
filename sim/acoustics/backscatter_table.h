#pragma once
// A tabulated bottom backscattering cross section σ(θ) for the renderer's hot loop.
//
// Any model S_b(θ) (APL-UW TR 9407, Lambert, ...) is evaluated once, for one frequency and
// sediment, on a uniform grazing grid over 0..90°, storing the LINEAR cross section
// σ = 10^(S_b/10). Lookups interpolate σ linearly between grid points: no allocation, no
// exceptions, one clamp and one multiply-add. With the default 0.05° step the interpolation error
// against direct evaluation is below 0.05 dB over 1-90° for the APL-UW sediments (tested).
#include <cstddef>
#include <functional>
#include <numbers>
#include <vector>

#include "sim/acoustics/apl_sediment.h"
#include "sim/acoustics/bottom_backscatter_lambert.h"
#include "sim/seabed/sediment.h"
#include "units/angles.h"

namespace sonarloop::acoustics {

// Bottom backscatter models a table can be built from.
enum class BottomModel {
  kApl,      // APL-UW TR 9407 (bottom_backscatter_apl.h)
  kLambert,  // Lambert's law (bottom_backscatter_lambert.h)
};

// Default grid step: 0.05° in radians.
inline constexpr double kBackscatterTableStepRad = 0.05 * kRadPerDeg;

class BackscatterTable {
 public:
  // Tabulates sigma_linear(grazing_rad) at 0, step, 2·step, ... up to π/2 (the last point is
  // exactly π/2). sigma_linear must return a finite value >= 0. step_rad > 0.
  explicit BackscatterTable(const std::function<double(double)>& sigma_linear,
                            double step_rad = kBackscatterTableStepRad);

  // Linear σ(θ) (m²/m²/sr). θ is clamped to [0, π/2]; NaN reads as 0.
  double sigma(double grazing_rad) const noexcept {
    double x = grazing_rad * inv_step_;
    x = x > 0.0 ? x : 0.0;  // also maps NaN to 0
    x = x < last_index_ ? x : last_index_;
    const auto i = static_cast<std::size_t>(x);
    const double t = x - static_cast<double>(i);
    // values_ has one padding entry past π/2, so i + 1 is always valid
    return values_[i] + t * (values_[i + 1] - values_[i]);
  }

  // 10·log10 σ(θ), dB (−inf where σ = 0).
  double sigma_db(double grazing_rad) const;

  double step_rad() const { return step_rad_; }
  // Number of grid points (excluding the padding entry).
  std::size_t size() const { return values_.size() - 1; }

 private:
  double step_rad_;
  double inv_step_;
  double last_index_;           // grid coordinate of π/2
  std::vector<double> values_;  // σ at grid points, plus one copy of the last (padding)
};

// Table for a sediment of sim/seabed/sediment.h at one frequency.
// kApl uses apl_sediment(id) and the APL-UW model with water sound speed c1_m_s;
// kLambert ignores the sediment and frequency and uses μ = lambert_mu_db.
// Throws std::invalid_argument for a bad sediment id, frequency or sound speed.
BackscatterTable make_backscatter_table(seabed::SedimentId id, double freq_hz, BottomModel model,
                                        double c1_m_s = kAplTableSoundSpeed_m_s,
                                        double lambert_mu_db = kMackenzieLambertMuDb,
                                        double step_rad = kBackscatterTableStepRad);

}  // namespace sonarloop::acoustics
