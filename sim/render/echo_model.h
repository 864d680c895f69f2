#pragma once
// The acoustic terms both ping renderers share (ping_renderer.h), computed once per sonar: the
// sonar equation per surface element, the bottom and target scattering tables, the beam patterns,
// the along-track sampling of the horizontal beam or strip, and the end of every ping (thermal
// noise, pulse blur, speckle). A renderer only finds what the ping sees and where; everything it
// adds to a line goes through here, so the two renderers differ in geometry only.
//
// The energetic sonar equation (Pailhas et al. 2010, Sec. 2.3; docs/physics.md §0, §3), linear:
//
//   I = SL · G_v(δ) · G_h · σ(θ) · dA / r⁴ · e^(−2αr)
//
// SL source level (in dB: tests/sim/acoustics/oracles/sonar_equation.h), G_v the two-way vertical
// pattern about the depression axis and G_h the horizontal one (acoustics/beam_pattern.h), σ the
// backscattering cross-section per unit area per steradian at the local grazing angle θ (APL-UW TR
// 9407 or Lambert, acoustics/backscatter_table.h; a target facet's Lambert μ·cos²θ,
// acoustics/target_scattering.h, plus the specular term of acoustics/target_specular.h when the
// sonar asks for it), dA the area of the element, α the Francois–Garrison absorption
// (acoustics/absorption.h). For an element seen under a vertical angle dδ across a horizontal
// width W (strip: W metres; beam: W = r·w_j, w_j the along-track sample's share of ∫G_h dψ) at
// incidence θ_i from its normal, dA = r·dδ·W / cos θ_i, so
//
//   I = SL · G_v · σ(θ) / cos θ_i · dδ · W · e^(−2αr) / r³          (seabed, cos θ_i = sin θ)
//   I = SL · G_v · μ cos θ_i · dδ · W · e^(−2αr) / r³                (Lambert target facet)
#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/render/ping_renderer.h"

namespace sonarloop::render {

// Adds `energy` spread uniformly over slant ranges [r − width/2, r + width/2] (in bins) to acc.
void splat(std::vector<double>& acc, double r_bins, double width_bins, double energy);

// The trace of (target, side) in `traces`, appended if new.
TargetTrace& trace_of(std::vector<TargetTrace>& traces, int target, int side);
// Widens [first, last] (-1: empty) to hold `bin`.
void extend_bins(int& first, int& last, int bin);

class EchoModel {
 public:
  EchoModel(const SonarSetup& sonar, const Fidelity& fidelity);

  const SonarSetup& sonar() const { return sonar_; }
  bool strip() const { return strip_; }

  // Along-track samples: offsets across the strip (m) or angles across the main lobe (rad), and
  // their weights W: metres of strip, or radians of ∫G_h dψ (Σ weights = ∫G_h dψ).
  const std::vector<float>& along() const { return along_; }
  const std::vector<float>& along_weight() const { return along_weight_; }

  // Two-way vertical intensity pattern G_v for sin(δ − depression) (exact: two sines' worth).
  double vertical_pattern(double off_axis_sin) const;
  // The same, tabulated (linear interpolation on a grid fine enough for < 1e-5 relative error
  // at the main lobe; profile renderer's inner loop).
  double vertical_pattern_fast(double off_axis_sin) const {
    double x = (off_axis_sin + 1.0) * pattern_scale_;
    x = x > 0.0 ? x : 0.0;
    x = x < pattern_last_ ? x : pattern_last_;
    const auto i = static_cast<std::size_t>(x);
    const double t = x - static_cast<double>(i);
    return pattern_[i] + t * (pattern_[i + 1] - pattern_[i]);
  }

  // SL · e^(−2αr) / r³: the range terms of the sonar equation for a unit dδ·W (see above),
  // and the same at the centre of each range bin (range_factor_at_bin()[k], k < bins).
  double range_factor(double r) const;
  const std::vector<double>& range_factor_at_bin() const { return range_factor_bin_; }

  // Seabed: σ(θ) for a sediment at grazing θ (rad), and σ(θ)/sin θ looked up by sin θ (the
  // profile renderer has sin θ = cos θ_i from a dot product, not the angle). sin θ below
  // kMinCosIncidence reads as kMinCosIncidence (a grazing element keeps a finite footprint).
  double seabed_sigma(int sediment, double grazing_rad) const;
  double seabed_sigma_over_sin(int sediment, double sin_grazing) const {
    if (sin_grazing >= kSigmaTableMaxSin) return seabed_sigma_over_sin_exact(sediment, sin_grazing);
    double x = sin_grazing * sos_scale_;
    x = x > 0.0 ? x : 0.0;  // also maps NaN to 0
    const auto i = static_cast<std::size_t>(x);
    const double t = x - static_cast<double>(i);
    const float* v = sigma_over_sin_[static_cast<std::size_t>(sediment)].data();
    return v[i] + t * (v[i + 1] - v[i]);
  }
  // σ/sin θ from the angle table (any sin θ; slower: an arcsine)
  double seabed_sigma_over_sin_exact(int sediment, double sin_grazing) const;

  // How a target scatters: the Lambert μ of its facets, (1 − f)·R²/π
  // (acoustics/target_scattering.h), and the weight f·R² of the specular Kirchhoff term
  // (acoustics/target_specular.h), R the impedance reflectance and f the sonar's
  // target_specular_fraction.
  struct TargetScatter {
    double mu = 0.0;
    double specular_weight = 0.0;
  };
  TargetScatter target_scatter(const scene::Scene& scene, int target) const;

  // The echo of a ray tube (meta: solid angle, dδ, G_v) hitting a surface at range r with
  // incidence cosine cos_i: the intensity it adds and the slant-range width (bins) its footprint
  // spans, r·dδ·tan θ_i. Seabed: σ from the sediment at grazing asin(cos_i); target:
  // (μ·cos²θ_i + f·R²·σ_spec(θ_i)) / cos θ_i.
  struct TubeEcho {
    double intensity = 0.0;
    double width_bins = 0.0;
  };
  TubeEcho seabed_tube(const RayMeta& m, double r, double cos_i, int sediment) const;
  TubeEcho target_tube(const RayMeta& m, double r, double cos_i, const TargetScatter& t) const;
  // SL · G_v · dΩ · e^(−2αr) / r² of a tube (dΩ: the strip's solid angle is its dδ·width / r)
  double tube_spread(const RayMeta& m, double r) const {
    const double d_omega = m.solid_angle / (strip_ ? r : 1.0);
    return source_level_lin_ * m.pattern * d_omega * std::exp(-alpha_np_ * r) / (r * r);
  }

  // The end of every ping: allocates and zeroes the accumulators (start_lines; the labels' too
  // when options.labels, bin_labels.h), then, over the rendered window only (RenderOptions' range
  // window; the lines are zero outside it), labels the bins if asked, adds thermal noise, blurs
  // to the pulse's range resolution and applies speckle drawn from (seed, ping_index, side) from
  // the window's first bin on, writing the lines (finish_lines).
  void start_lines(const RenderOptions& options, PingScratch& scratch) const;
  void finish_lines(const RenderOptions& options, std::uint64_t seed, std::uint64_t ping_index,
                    double altitude, PingScratch& scratch, PingLines& out) const;

  // speckle_model pulse (sonar.h): the bins [k0, k1) of `line` from the mean energies `acc`,
  // through the pulse on the receiver's raw samples (acoustics/pulse_speckle.h; the pulse is
  // round(range resolution / raw sample) samples long) and the recorder's downsampling
  // (acoustics/recorder_downsample.h), drawn from (seed, ping_index, side) like per-bin speckle.
  void pulse_speckle_line(const std::vector<double>& acc, int k0, int k1, std::uint64_t seed,
                          std::uint64_t ping_index, int side, PingScratch& scratch,
                          std::vector<float>& line) const;
  // speckle_model per_bin: the bins [k0, k1) of `line` from `acc` blurred over `blur` bins (read
  // from first_read on; acc then holds the blurred means) with one exponential speckle draw per
  // bin from (seed, ping_index, side) when `speckle`.
  void per_bin_line(std::vector<double>& acc, int k0, int k1, int first_read, int blur,
                    bool speckle, std::uint64_t seed, std::uint64_t ping_index, int side,
                    std::vector<float>& line) const;

  // The floor of cos θ_i in dA = r²·dΩ / cos θ_i.
  static constexpr double kMinCosIncidence = 1e-3;
  // σ/sin θ is tabulated uniformly in sin θ up to here (θ ≈ 76°) and looked up by angle above
  // it, where a uniform grid in sin θ would be too coarse in angle for the specular peak.
  static constexpr double kSigmaTableMaxSin = 0.97;
  // An element's echo is spread over at most this many bins (almost tangent to the surface).
  static constexpr double kMaxSpreadBins = 32.0;

 private:
  SonarSetup sonar_;
  bool strip_;
  std::vector<float> along_;
  std::vector<float> along_weight_;
  std::vector<acoustics::BackscatterTable> sigma_;  // per SedimentId
  // σ(θ)/sin θ on a uniform grid of sin θ per sediment, and the sin θ above which the table is
  // not fine enough (near-normal incidence: exact lookups there)
  std::vector<std::vector<float>> sigma_over_sin_;
  double sos_scale_ = 0.0;
  double sos_last_ = 0.0;
  std::vector<float> pattern_;  // G_v on a uniform grid of sin(off axis) over [−1, 1]
  double pattern_scale_ = 0.0;
  double pattern_last_ = 0.0;
  double source_level_lin_ = 0.0;
  std::vector<double> range_factor_bin_;
  double alpha_np_ = 0.0;   // two-way absorption per metre (nepers of intensity)
  double noise_lin_ = 0.0;  // mean noise intensity per bin
  // the recorder's noise floor as a mean intensity per bin (empty: none), and the intensity at
  // full scale of each bin the transmit ring-down saturates
  std::vector<double> floor_bin_;
  std::vector<double> ringdown_full_scale_;
  double k_half_height_ = 0.0;
};

}  // namespace sonarloop::render
