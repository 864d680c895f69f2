#include "sim/render/echo_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/rng.h"
#include "sim/acoustics/beam_pattern.h"
#include "sim/acoustics/noise.h"
#include "sim/acoustics/pulse_speckle.h"
#include "sim/acoustics/recorder_downsample.h"
#include "sim/acoustics/speckle.h"
#include "sim/acoustics/target_scattering.h"
#include "sim/acoustics/target_specular.h"
#include "sim/acoustics/transmit_ringdown.h"
#include "sim/render/bin_labels.h"
#include "sim/render/quantise.h"
#include "sim/seabed/sediment.h"

namespace sonarloop::render {
namespace {

constexpr double kWaterDensity_kg_m3 = 1027.0;  // docs/physics.md §4 impedance table (Z1)
// Grid of the tabulated vertical pattern: points per unit of sin(off axis), at least
// kPatternPointsPerLobe per main-lobe half width (sin = λ/height).
constexpr int kPatternMinPoints = 16384;
constexpr double kPatternPointsPerLobe = 2048.0;
// σ/sin θ table: points uniform in sin θ over [0, kSigmaTableMaxSin]
constexpr int kSigmaTablePoints = 8192;

}  // namespace

void splat(std::vector<double>& acc, double r_bins, double width_bins, double energy) {
  const auto n = static_cast<double>(acc.size());
  if (width_bins <= 1e-6) {
    if (r_bins >= 0.0 && r_bins < n) acc[static_cast<std::size_t>(r_bins)] += energy;
    return;
  }
  const double a = r_bins - 0.5 * width_bins;
  const double b = r_bins + 0.5 * width_bins;
  const double density = energy / width_bins;
  const int k0 = std::max(0, static_cast<int>(std::floor(a)));
  const int k1 = std::min(static_cast<int>(n) - 1, static_cast<int>(std::floor(b)));
  for (int k = k0; k <= k1; ++k) {
    const double overlap = std::min(b, k + 1.0) - std::max(a, static_cast<double>(k));
    acc[static_cast<std::size_t>(k)] += density * overlap;
  }
}

TargetTrace& trace_of(std::vector<TargetTrace>& traces, int target, int side) {
  for (auto& t : traces) {
    if (t.target == target && t.side == side) return t;
  }
  traces.push_back(TargetTrace{target, side});
  return traces.back();
}

void extend_bins(int& first, int& last, int bin) {
  if (first < 0 || bin < first) first = bin;
  if (last < 0 || bin > last) last = bin;
}

EchoModel::EchoModel(const SonarSetup& s, const Fidelity& fidelity)
    : sonar_(s), strip_(s.desc.along_track == AlongTrackModel::kStrip) {
  const SonarDesc& sd = s.desc;
  // along-track samples: offsets across the strip, or angles across the main lobe weighted by
  // the two-way horizontal pattern
  const int n_along = std::max(1, fidelity.along_track_rays);
  along_.resize(static_cast<std::size_t>(n_along));
  along_weight_.resize(static_cast<std::size_t>(n_along));
  if (strip_) {
    const double w = s.along_track_resolution_m;
    for (int j = 0; j < n_along; ++j) {
      along_[static_cast<std::size_t>(j)] = static_cast<float>(-0.5 * w + (j + 0.5) * w / n_along);
      along_weight_[static_cast<std::size_t>(j)] = static_cast<float>(w / n_along);  // metres
    }
  } else {
    const double psi_null = acoustics::first_null_rad(sd.array_length_m, s.wavelength_m);
    double sum = 0.0;
    for (int j = 0; j < n_along; ++j) {
      const double psi = n_along == 1 ? 0.0 : -psi_null + (j + 0.5) * 2.0 * psi_null / n_along;
      const double b = acoustics::line_array_pattern(psi, sd.array_length_m, s.wavelength_m);
      along_[static_cast<std::size_t>(j)] = static_cast<float>(psi);
      along_weight_[static_cast<std::size_t>(j)] = static_cast<float>(b * b * b * b);
      sum += b * b * b * b;
    }
    // the weights integrate the two-way horizontal pattern: Σ w_j = ∫ G_h dψ
    for (auto& w : along_weight_)
      w = static_cast<float>(w * s.horizontal_beam_integral_rad / sum);
  }

  // bottom backscatter per sediment, by angle and by sin(angle)
  sos_scale_ = kSigmaTablePoints / kSigmaTableMaxSin;
  sos_last_ = kSigmaTablePoints;
  for (std::size_t id = 0; id < seabed::sediment_table().size(); ++id) {
    sigma_.push_back(acoustics::make_backscatter_table(
        static_cast<seabed::SedimentId>(id), sd.frequency_hz, sd.bottom_model,
        acoustics::kAplTableSoundSpeed_m_s, sd.lambert_mu_db));
    std::vector<float> t(static_cast<std::size_t>(kSigmaTablePoints) + 2);
    for (int k = 0; k <= kSigmaTablePoints + 1; ++k) {
      const double x = std::max(k / sos_scale_, kMinCosIncidence);
      t[static_cast<std::size_t>(k)] = static_cast<float>(sigma_.back().sigma(std::asin(x)) / x);
    }
    sigma_over_sin_.push_back(std::move(t));
  }

  // vertical pattern table over sin(off axis) in [−1, 1]
  k_half_height_ = std::numbers::pi / s.wavelength_m * sd.array_height_m;
  const double lobe = s.wavelength_m / std::max(sd.array_height_m, 1e-9);  // sin of first null
  const int points =
      std::max(kPatternMinPoints, static_cast<int>(std::ceil(2.0 / lobe * kPatternPointsPerLobe)));
  pattern_scale_ = points / 2.0;
  pattern_last_ = points;
  pattern_.resize(static_cast<std::size_t>(points) + 2);
  for (int k = 0; k <= points + 1; ++k)
    pattern_[static_cast<std::size_t>(k)] =
        static_cast<float>(vertical_pattern(std::min(1.0, k / pattern_scale_ - 1.0)));

  source_level_lin_ = std::pow(10.0, sd.source_level_db / 10.0);
  alpha_np_ = 0.2 * std::numbers::ln10 * s.alpha_db_per_m;  // two-way, per metre
  range_factor_bin_.resize(static_cast<std::size_t>(s.bins));
  for (int k = 0; k < s.bins; ++k)
    range_factor_bin_[static_cast<std::size_t>(k)] = range_factor((k + 0.5) * sd.bin_size_m);
  // received thermal noise in the receiver band, reduced by the array's directivity index
  const double di =
      acoustics::directivity_index_rect_db(sd.array_length_m, sd.array_height_m, s.wavelength_m);
  const double nl = acoustics::noise_band_level_db(sd.frequency_hz, s.bandwidth_hz) - di;
  noise_lin_ = std::pow(10.0, nl / 10.0);
  // the recorder's floor, given after TVG and gain, as the echo intensity that reads as it
  if (sd.noise_floor_db_fs < 0.0) {
    floor_bin_.resize(static_cast<std::size_t>(s.bins));
    for (int k = 0; k < s.bins; ++k)
      floor_bin_[static_cast<std::size_t>(k)] =
          intensity_at_level_db_fs(s, sd.noise_floor_db_fs, (k + 0.5) * sd.bin_size_m);
  }
  const int ring =
      std::min(s.bins, acoustics::ringdown_bins(sd.ringdown_s, s.sound_speed_m_s, sd.bin_size_m));
  for (int k = 0; k < ring; ++k)
    ringdown_full_scale_.push_back(intensity_at_level_db_fs(s, 0.0, (k + 0.5) * sd.bin_size_m));
}

double EchoModel::vertical_pattern(double off_axis_sin) const {
  const double bv = acoustics::sinc(k_half_height_ * off_axis_sin);
  return bv * bv * bv * bv;
}

double EchoModel::range_factor(double r) const {
  return source_level_lin_ * std::exp(-alpha_np_ * r) / (r * r * r);
}

double EchoModel::seabed_sigma(int sediment, double grazing_rad) const {
  return sigma_[static_cast<std::size_t>(sediment)].sigma(grazing_rad);
}

double EchoModel::seabed_sigma_over_sin_exact(int sediment, double sin_grazing) const {
  const double x = std::clamp(sin_grazing, kMinCosIncidence, 1.0);
  return seabed_sigma(sediment, std::asin(x)) / x;
}

EchoModel::TargetScatter EchoModel::target_scatter(const scene::Scene& scene, int target) const {
  // design choices (target_scattering.h, target_specular.h): Lambert μ = (1 − f)·R²/π and the
  // specular weight f·R², R the impedance reflectance
  const double z_water = acoustics::acoustic_impedance(kWaterDensity_kg_m3, sonar_.sound_speed_m_s);
  const double r = acoustics::impedance_reflectance(
      z_water, scene.targets()[static_cast<std::size_t>(target)].impedance_rayl);
  const double f = sonar_.desc.target_specular_fraction;
  const double mu = acoustics::lambert_mu_from_reflectance(r);
  return {f > 0.0 ? (1.0 - f) * mu : mu, f * r * r};
}

namespace {

// the tube's slant-range extent on the surface: r·dδ·tan θ_i, in bins
double tube_width_bins(const RayMeta& m, double r, double cos_i, double bin_m) {
  const double tan_i = std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i)) / cos_i;
  return std::min(r * m.depression_width * tan_i / bin_m, EchoModel::kMaxSpreadBins);
}

}  // namespace

EchoModel::TubeEcho EchoModel::seabed_tube(const RayMeta& m, double r, double cos_i,
                                           int sediment) const {
  cos_i = std::max(cos_i, kMinCosIncidence);
  const double d_omega = m.solid_angle / (strip_ ? r : 1.0);
  const double spread =
      source_level_lin_ * m.pattern * d_omega * std::exp(-alpha_np_ * r) / (r * r);
  const double grazing = std::asin(std::min(1.0, cos_i));
  return {spread * seabed_sigma(sediment, grazing) / cos_i,
          tube_width_bins(m, r, cos_i, sonar_.desc.bin_size_m)};
}

EchoModel::TubeEcho EchoModel::target_tube(const RayMeta& m, double r, double cos_i,
                                           const TargetScatter& t) const {
  cos_i = std::max(cos_i, kMinCosIncidence);
  const double d_omega = m.solid_angle / (strip_ ? r : 1.0);
  const double spread =
      source_level_lin_ * m.pattern * d_omega * std::exp(-alpha_np_ * r) / (r * r);
  const double width = tube_width_bins(m, r, cos_i, sonar_.desc.bin_size_m);
  if (t.specular_weight <= 0.0) return {spread * t.mu * cos_i, width};  // Lambert: μ cos²θ / cos θ
  const double specular =
      t.specular_weight *
      acoustics::kirchhoff_facet_backscatter(cos_i, sonar_.desc.target_rms_slope) / cos_i;
  return {spread * (t.mu * cos_i + specular), width};
}

void EchoModel::start_lines(const RenderOptions& options, PingScratch& scratch) const {
  const auto nb = static_cast<std::size_t>(sonar_.bins);
  scratch.accum[0].assign(nb, 0.0);
  scratch.accum[1].assign(nb, 0.0);
  start_bin_labels(options, sonar_.bins, scratch.labels);
}

void EchoModel::pulse_speckle_line(const std::vector<double>& acc, int k0, int k1,
                                   std::uint64_t seed, std::uint64_t ping_index, int side,
                                   PingScratch& scratch, std::vector<float>& line) const {
  const int m = sonar_.desc.raw_samples_per_bin;
  const double raw_m = sonar_.desc.bin_size_m / m;
  const int taps = std::max(1, static_cast<int>(std::lround(sonar_.range_resolution_m / raw_m)));
  // the pulse reaches taps - 1 raw samples back from the window's first
  const int raw0 = std::max(0, k0 * m - (taps - 1));
  const int raw1 = k1 * m;
  if (raw1 <= raw0) return;
  auto& mean = scratch.raw_mean;
  auto& out = scratch.raw_intensity;
  mean.resize(static_cast<std::size_t>(raw1 - raw0));
  out.resize(mean.size());
  // each raw sample's cell has its bin's mean intensity, so that the pulse's average over its
  // taps is the per-bin blur's mean (over round(resolution / bin) bins)
  for (int j = raw0; j < raw1; ++j)
    mean[static_cast<std::size_t>(j - raw0)] = acc[static_cast<std::size_t>(j / m)];
  Rng rng(seed, RngStream::kSpeckle, ping_index, static_cast<std::uint64_t>(side));
  acoustics::pulse_speckle(mean, taps, rng, out);
  for (int k = k0; k < k1; ++k) {
    const auto first = static_cast<std::size_t>(k * m - raw0);
    line[static_cast<std::size_t>(k)] = static_cast<float>(acoustics::downsample(
        std::span<const double>(out.data() + first, static_cast<std::size_t>(m)),
        sonar_.desc.downsample));
  }
}

void EchoModel::finish_lines(const RenderOptions& options, std::uint64_t seed,
                             std::uint64_t ping_index, double altitude, PingScratch& scratch,
                             PingLines& out) const {
  const int bins = sonar_.bins;
  const auto nb = static_cast<std::size_t>(bins);
  const double dr = sonar_.desc.bin_size_m;
  out.port.assign(nb, 0.0f);
  out.stbd.assign(nb, 0.0f);
  out.altitude_m = altitude;
  const double r_max = std::min(options.range_max_m, sonar_.desc.max_range_m);
  const int k0 = std::clamp(static_cast<int>(std::floor(options.range_min_m / dr)), 0, bins);
  const int k1 = std::clamp(static_cast<int>(std::ceil(r_max / dr)), 0, bins);
  const int blur = std::max(1, static_cast<int>(std::lround(sonar_.range_resolution_m / dr)));
  // the labels read the echoes before noise, blur and speckle change them
  finish_bin_labels(options, bins, k0, k1, blur, scratch.accum, scratch.labels, out);
  if (!(altitude > 0.0)) return;  // out of the water: silent lines
  const bool speckle = options.speckle && sonar_.desc.speckle;
  const bool noise = options.noise && sonar_.desc.noise;
  // only the window's bins are finished (a chip renders a few metres of a long range): the
  // blur of its first bin reads blur - 1 bins before it
  const int first_read = std::max(0, k0 - blur + 1);
  for (int side = 0; side < 2; ++side) {
    if (!(options.side_mask & (1 << side))) continue;
    auto& acc = scratch.accum[side];
    auto& line = side == 0 ? out.port : out.stbd;
    if (noise) {
      for (int k = k0; k < k1; ++k)
        acc[static_cast<std::size_t>(k)] += noise_lin_;
    }
    // the recorder's floor: noise like the sea's, on every raw sample
    if (options.noise && !floor_bin_.empty()) {
      for (int k = k0; k < k1; ++k)
        acc[static_cast<std::size_t>(k)] += floor_bin_[static_cast<std::size_t>(k)];
    }
    // speckle through the pulse on the raw samples, then the recorder's downsampling
    if (speckle && sonar_.desc.speckle_model == SpeckleModel::kPulse) {
      pulse_speckle_line(acc, k0, k1, seed, ping_index, side, scratch, line);
    } else {
      per_bin_line(acc, k0, k1, first_read, blur, speckle, seed, ping_index, side, line);
    }
    // the transmit pulse and ring-down saturate the record's first bins
    const int ring_end = std::min(k1, static_cast<int>(ringdown_full_scale_.size()));
    for (int k = k0; k < ring_end; ++k)
      line[static_cast<std::size_t>(k)] =
          static_cast<float>(ringdown_full_scale_[static_cast<std::size_t>(k)]);
  }
}

void EchoModel::per_bin_line(std::vector<double>& acc, int k0, int k1, int first_read, int blur,
                             bool speckle, std::uint64_t seed, std::uint64_t ping_index, int side,
                             std::vector<float>& line) const {
  // pulse longer than a bin: moving average over the range resolution (energy preserving)
  if (blur > 1) {
    double sum = 0.0;
    for (int k = first_read; k < k1; ++k) {
      sum += acc[static_cast<std::size_t>(k)];
      if (k - blur >= first_read) sum -= acc[static_cast<std::size_t>(k - blur)];
      if (k >= k0) line[static_cast<std::size_t>(k)] = static_cast<float>(sum / blur);
    }
    for (int k = k0; k < k1; ++k)
      acc[static_cast<std::size_t>(k)] = line[static_cast<std::size_t>(k)];
  }
  // fully developed speckle from the stream (seed, ping, side), drawn from the window's first
  // bin on
  if (speckle) {
    Rng rng(seed, RngStream::kSpeckle, ping_index, static_cast<std::uint64_t>(side));
    for (int k = k0; k < k1; ++k) {
      const auto i = static_cast<std::size_t>(k);
      line[i] = static_cast<float>(acoustics::apply_speckle(acc[i], rng.uniform_pos()));
    }
  } else {
    for (int k = k0; k < k1; ++k) {
      const auto i = static_cast<std::size_t>(k);
      line[i] = static_cast<float>(acc[i]);
    }
  }
}

}  // namespace sonarloop::render
