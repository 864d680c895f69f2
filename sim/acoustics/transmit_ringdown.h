#pragma once
// The transmit pulse and ring-down at the start of a record (docs/physics.md §3, "Receive
// chain"). While a sidescan transmits, its receiver hears the transmitter directly, and after
// the pulse the transducer rings on for a while: the first samples of every ping are
// saturated, then the record drops to the water column within a sample. The real Iver2 file of
// docs/realism.md shows it: its first 8 samples (0.23 m, about 320 µs at 1460 m/s) are at full
// scale in every ping, sample 9 is at about twice the water column, and the rest are echoes
// (measured on that file, docs/physics.md §3 "Receive chain"; the source is the measurement).
//
// The model: the receiver is saturated from transmission until ringdown_s; a bin whose centre's
// two-way time 2·(k + 0.5)·dr / c falls before it records full scale.

namespace sonarloop::acoustics {

// The number of bins from the start of the record whose centre time falls before ringdown_s:
// the k with 2·(k + 0.5)·bin_size_m / c < ringdown_s (0 for ringdown_s <= 0).
int ringdown_bins(double ringdown_s, double sound_speed_m_s, double bin_size_m);

}  // namespace sonarloop::acoustics
