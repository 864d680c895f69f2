#pragma once
// Ambient noise: molecular-agitation (thermal) noise, the floor that dominates above ~100 kHz.
//
// Mellen, "The thermal-noise limit in the detection of underwater acoustic signals", JASA 24(5)
// 478-480 (1952), as used by Pailhas et al. (2010) and listed in docs/physics.md §0/§4:
//   NL(f) = -15 + 20·log10(f / 1 kHz)      dB re 1 µPa²/Hz
// Validity: above ~50 kHz, where thermal noise exceeds wind/shipping noise (Wenz 1962);
// at lower frequencies this is a lower bound only.
namespace sonarloop::acoustics {

// Thermal noise spectrum level, dB re 1 µPa²/Hz. freq_hz > 0.
double thermal_noise_spectrum_db(double freq_hz);

// Thermal noise level in a band of width bandwidth_hz centred on freq_hz, dB re 1 µPa²:
// NL + 10·log10(B), treating the spectrum as flat across the band (B << f).
double noise_band_level_db(double freq_hz, double bandwidth_hz);

}  // namespace sonarloop::acoustics
