#include "sim/render/quantise.h"

#include <algorithm>
#include <cmath>

#include "sim/acoustics/tvg.h"

namespace sonarloop::render {
namespace {

// The largest value of a signed 16-bit sample (SampleType::kInt16).
constexpr double kInt16FullScale = 32767.0;

// TVG gain as a linear intensity factor at the centre of every bin would be recomputed per
// sample; it is cheap (one log and one exp) next to rendering, so no table is kept.
template <class T>
void quantise(const SonarSetup& s, std::span<const float> in, std::span<T> out, double full_scale,
              bool clip) {
  const std::size_t n = std::min(in.size(), out.size());
  for (std::size_t k = 0; k < n; ++k) {
    const double r = (static_cast<double>(k) + 0.5) * s.desc.bin_size_m;
    const double a = relative_amplitude(s, in[k], r) * full_scale;
    if (clip) {
      out[k] = static_cast<T>(std::lround(std::clamp(a, 0.0, full_scale)));
    } else {
      out[k] = static_cast<T>(a);
    }
  }
}

}  // namespace

double full_scale_level_db(const SonarSetup& s) {
  // TVG-corrected echo of a cell at normal incidence: SL + S_b + 10 log(cell), where the cell
  // after the TVG's range law is bin × horizontal beam integral (area law, kBeam) or
  // bin × strip width (point law, kStrip)
  const double cell = s.desc.along_track == AlongTrackModel::kStrip
                          ? s.desc.bin_size_m * s.along_track_resolution_m
                          : s.desc.bin_size_m * s.horizontal_beam_integral_rad;
  return s.desc.source_level_db + kFullScaleStrengthDb + 10.0 * std::log10(cell);
}

double relative_amplitude(const SonarSetup& s, double intensity, double range_m) {
  if (!(intensity > 0.0)) return 0.0;
  const double level =
      10.0 * std::log10(intensity) + acoustics::tvg_db(range_m, s.alpha_db_per_m, s.tvg);
  return std::pow(10.0, (level - full_scale_level_db(s) + s.desc.gain_db) / 20.0);
}

double intensity_at_level_db_fs(const SonarSetup& s, double level_db_fs, double range_m) {
  const double level = level_db_fs + full_scale_level_db(s) - s.desc.gain_db -
                       acoustics::tvg_db(range_m, s.alpha_db_per_m, s.tvg);
  return std::pow(10.0, level / 10.0);
}

void quantise_line(const SonarSetup& s, std::span<const float> in, std::span<std::uint8_t> out) {
  quantise(s, in, out, 255.0, true);
}

void quantise_line(const SonarSetup& s, std::span<const float> in, std::span<std::uint16_t> out) {
  const double full_scale = s.desc.sample_type == SampleType::kInt16 ? kInt16FullScale : 65535.0;
  quantise(s, in, out, full_scale, true);
}

void quantise_line(const SonarSetup& s, std::span<const float> in, std::span<float> out) {
  quantise(s, in, out, 1.0, false);
}

}  // namespace sonarloop::render
