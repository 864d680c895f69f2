#pragma once
// A sidescan sonar: what a sonar YAML file describes (SonarDesc, plain data), and the derived
// quantities the renderer needs, computed once per (sonar, water) pair (SonarSetup).
//
// The image geometry follows Pailhas et al. (2010), Sec. 2.3: each ping is a port and a
// starboard line of range bins ("pixels") of bin_size_m in slant range, out to max_range_m.
#include <cstdint>
#include <optional>
#include <string>

#include "sim/acoustics/backscatter_table.h"
#include "sim/acoustics/beam_pattern.h"
#include "sim/acoustics/recorder_downsample.h"
#include "sim/acoustics/tvg.h"
#include "sim/scene/scene_desc.h"

namespace sonarloop::render {

// kInt16: 16-bit samples of the X41 "int16" format (SampleFormat 3) kept within the signed
// range, full scale 32767, as Sea Scan recorders write them (tests/data/xtf/scotsman-iver2.xtf:
// no sample above 32767). kUint16 uses the whole unsigned range, full scale 65535.
enum class SampleType { kUint8, kUint16, kFloat32, kInt16 };

// How speckle is drawn (docs/physics.md §3, "Receive chain").
enum class SpeckleModel {
  kPerBin,  // one exponential draw per bin after the pulse's smoothing (acoustics/speckle.h)
  kPulse,   // a complex field on the raw samples through the pulse (acoustics/pulse_speckle.h):
            // correlated over the range resolution
};

// How the along-track (horizontal) beam is modelled.
enum class AlongTrackModel {
  kBeam,   // a real line array: the two-way pattern of array_length_m; resolution grows as r·β
  kStrip,  // a focused / synthetic-aperture-like beam: a strip of along_track_resolution_m at
           // every range (the paper's isotropic pixel resolution)
};

struct SonarDesc {
  std::string name = "sidescan";
  double frequency_hz = 300e3;      // centre frequency
  double source_level_db = 210.0;   // dB re 1 µPa at 1 m
  double pulse_length_s = 0.0;      // CW pulse; 0 = the pulse whose resolution is one bin
  double chirp_bandwidth_hz = 0.0;  // LFM bandwidth after matched filtering; 0 = CW
  double array_length_m = 0.5;      // along-track aperture (horizontal beam)
  double array_height_m = 0.02;     // vertical aperture (vertical beam)
  double depression_deg = 15.0;     // acoustic axis below horizontal
  double max_range_m = 50.0;        // slant range per side
  double bin_size_m = 0.05;         // range bin (pixel) in slant range
  double ping_period_s = 0.0;       // 0 = two-way travel time of max_range_m
  AlongTrackModel along_track = AlongTrackModel::kBeam;
  double along_track_resolution_m = 0.0;  // kStrip: strip width; 0 = bin_size_m
  SampleType sample_type = SampleType::kUint16;
  // Time-varied gain law; empty = auto: area (30 log r) for kBeam, whose cell grows with range,
  // point (40 log r) for kStrip, whose cell does not.
  std::optional<acoustics::TvgLaw> tvg;
  double gain_db = 0.0;  // added before quantisation (see quantise.h)
  acoustics::BottomModel bottom_model = acoustics::BottomModel::kApl;
  double lambert_mu_db = -27.0;  // for bottom_model kLambert
  // Targets: the share f of the reflected energy R² returned by the specular (Kirchhoff) term,
  // the rest by Lambert facets (acoustics/target_specular.h); 0 = Lambert only (the paper).
  double target_specular_fraction = 0.0;
  double target_rms_slope = 0.15;  // rms micro-slope per component s of the specular term
  bool speckle = true;             // fully developed speckle, drawn as speckle_model says
  bool noise = true;               // Mellen thermal noise in the receiver band
  // The receive chain: how speckle is drawn, the receiver's raw samples per recorded bin (more
  // than 1 with kPulse only) and how the recorder makes a bin of them (XTF DownsampleMethod).
  SpeckleModel speckle_model = SpeckleModel::kPerBin;
  int raw_samples_per_bin = 1;
  acoustics::Downsample downsample = acoustics::Downsample::kRms;
  // The recorder's noise floor: circular Gaussian noise of this mean power in dB re full scale²
  // after TVG and gain, on every raw sample (docs/physics.md §3, "Receive chain"); 0 = none.
  double noise_floor_db_fs = 0.0;
  // Transmit pulse and ring-down: the receiver is saturated from transmission until this time,
  // so the bins whose centre it reaches record full scale; 0 = none.
  double ringdown_s = 0.0;
  // Fidelity knobs (RenderOptions, ping_renderer.h): 0 = the default rule
  int rays_per_bin = 0;      // vertical rays per range bin on a flat seabed
  int along_track_rays = 0;  // rays across the horizontal beam or strip
};

// Derived, per (sonar, water): wavelengths, absorption, resolutions, timing.
struct SonarSetup {
  SonarDesc desc;
  double sound_speed_m_s = 1500.0;
  double wavelength_m = 0.0;
  double alpha_db_per_m = 0.0;      // Francois–Garrison at the centre frequency
  double range_resolution_m = 0.0;  // c·τ/2 or c/(2B)
  double bandwidth_hz = 0.0;        // receiver bandwidth (1/τ or B)
  double pulse_length_s = 0.0;
  int bins = 0;  // per side
  double ping_period_s = 0.0;
  double along_track_resolution_m = 0.0;             // kStrip width
  double horizontal_beamwidth_rad = 0.0;             // two-way -3 dB (kBeam)
  double horizontal_beam_integral_rad = 0.0;         // ∫ two-way horizontal intensity pattern dψ
  double vertical_beamwidth_rad = 0.0;               // one-way -3 dB
  double noise_spectrum_db = 0.0;                    // Mellen, dB re 1 µPa²/Hz
  acoustics::TvgLaw tvg = acoustics::TvgLaw::kArea;  // resolved (never auto)
  acoustics::SidescanArray array{};
};

// Computes the derived quantities. Throws std::invalid_argument for an impossible sonar
// (e.g. a bin smaller than a wavelength); ranges are validated by the YAML loader.
SonarSetup make_sonar_setup(const SonarDesc& desc, const scene::WaterDesc& water);

}  // namespace sonarloop::render
