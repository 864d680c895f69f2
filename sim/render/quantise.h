#pragma once
// From echo intensity to the numbers a sidescan records: time-varied gain, gain, and
// quantisation to the sonar's sample type (the last step of Pailhas et al. 2010, Sec. 2.3).
//
//   L(r)  = 10·log10 I(r) + TVG(r)                (TVG law of the sonar, acoustics/tvg.h)
//   A(r)  = 10^((L(r) - L_fs + gain_db)/20)        amplitude relative to full scale
//   sample = round(A · full_scale), clipped to [0, full_scale]   (uint8: 255, uint16: 65535,
//            int16: 32767, the largest value of a signed 16-bit sample)
//            A itself for float samples (not clipped)
//
// The full-scale level L_fs is the TVG-corrected echo of a seabed patch with backscattering
// strength kFullScaleStrengthDb seen broadside at normal incidence: rough rock (about -5 dB
// at steep grazing, docs/physics.md §2.5) just reaches full scale, sand sits 20-30 dB below, and
// strong target highlights clip, as on a real recorder with a fixed gain.
#include <cstdint>
#include <span>

#include "sim/render/ping_renderer.h"
#include "sim/render/sonar.h"

namespace sonarloop::render {

inline constexpr double kFullScaleStrengthDb = -5.0;

// L_fs in dB re 1 µPa² (TVG-corrected), see above.
double full_scale_level_db(const SonarSetup& sonar);

// Amplitude relative to full scale of one bin's intensity at slant range range_m (unclipped).
double relative_amplitude(const SonarSetup& sonar, double intensity, double range_m);

// The intensity at slant range range_m whose amplitude is level_db_fs dB re full scale
// (20·log10 of relative_amplitude): relative_amplitude's inverse.
double intensity_at_level_db_fs(const SonarSetup& sonar, double level_db_fs, double range_m);

// Quantises one side's line (near to far) into `out` (same length). Bin k is at the centre
// range (k + 0.5)·bin_size_m.
void quantise_line(const SonarSetup& sonar, std::span<const float> intensity,
                   std::span<std::uint8_t> out);
// 16-bit samples: full scale 65535 (SampleType::kUint16) or 32767 (SampleType::kInt16, the
// values are non-negative and fit a signed 16-bit sample as well).
void quantise_line(const SonarSetup& sonar, std::span<const float> intensity,
                   std::span<std::uint16_t> out);
void quantise_line(const SonarSetup& sonar, std::span<const float> intensity, std::span<float> out);

}  // namespace sonarloop::render
