#include "sim/acoustics/noise.h"

#include <cmath>

namespace sonarloop::acoustics {
namespace {

// Mellen (1952): spectrum level at 1 kHz, dB re 1 µPa²/Hz, rising 6 dB per octave.
constexpr double kThermalNoiseAt1KhzDb = -15.0;
constexpr double kThermalReferenceHz = 1000.0;  // the 1 kHz of that level

}  // namespace

double thermal_noise_spectrum_db(double freq_hz) {
  return kThermalNoiseAt1KhzDb + 20.0 * std::log10(freq_hz / kThermalReferenceHz);
}

double noise_band_level_db(double freq_hz, double bandwidth_hz) {
  return thermal_noise_spectrum_db(freq_hz) + 10.0 * std::log10(bandwidth_hz);
}

}  // namespace sonarloop::acoustics
