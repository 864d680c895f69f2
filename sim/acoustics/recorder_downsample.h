#pragma once
// The recorder's downsampling (docs/physics.md §3, "Receive chain"): a sidescan receiver samples
// faster than it records, and stores one value per recorded bin from M raw samples. XTF says
// which in its channel header (DownsampleMethod: 2 MAX, 4 RMS; Triton Imaging, "XTF File
// Format", rev. 35, XTFCHANINFO).
//   rms:      the mean of the M intensities (the RMS of the amplitudes)
//   max:      the largest (Sea Scan recorders; the Iver2 file of docs/realism.md): for M
//             independent exponential intensities of mean I the mean becomes I·H_M (H_M the
//             harmonic number: 1.5 for 2, 1.833 for 3) and the amplitude spread narrower
//   decimate: the first of the M (no filter: keeps the raw statistics)
#include <cstdint>
#include <span>

namespace sonarloop::acoustics {

enum class Downsample { kRms, kMax, kDecimate };

// One recorded bin from its raw samples' intensities (at least one).
double downsample(std::span<const double> raw_intensity, Downsample how);

// XTF's DownsampleMethod code for `how` (0 for decimation, which XTF does not name).
std::uint16_t xtf_downsample_method(Downsample how);

// The oracle: the mean of the largest of m independent exponential intensities of mean 1, H_m.
double mean_of_max_exponential(int m);

}  // namespace sonarloop::acoustics
