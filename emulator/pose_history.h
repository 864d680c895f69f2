#pragma once
// Each ping at the pose of its own time (`run --pose-from`): a short history of the external
// vehicle's pose samples, and the pose at any time from it.
//
// Why. An external vehicle sends its pose at 10-50 Hz while the sonar pings at its own rate
// (15 Hz by default). Taking the latest sample as it is renders several pings at one position
// and then jumps: the waterfall stutters. Instead every ping is rendered at the pose of the
// time it is due, from the samples around that time.
//
// Sample times. A sample is placed at the sender's own time stamp when it gives one (the UDP pose
// message's time_unix_ns), mapped onto the emulator's clock by a minimum-delay filter: offset =
// the smallest (arrival - stamp) seen, relaxed by kOffsetRelaxPerSecond per second of arrivals
// so that slow clock drift is followed. Network and scheduling jitter then does not move the
// samples: a vehicle moving evenly is rendered evenly. Samples without a stamp (NMEA 2000
// frames, whose rapid-update PGNs carry no time) are placed at their arrival time.
//
// The rule (pose_at(τ)), per part of the pose, each with its own samples (NMEA 2000 sends
// position, heading, attitude and depth in separate frames):
//   τ between two samples   linear interpolation; heading along the shorter way round
//   τ after the last        extrapolation from the last two samples' rate (velocity, turn rate,
//                           ...), for at most max_extrapolation_ns beyond the last (then held);
//                           with one sample, that sample. Counted as extrapolated (position)
//   τ before the first      the first sample
// The emulator asks for τ = (the ping's due time) - delay: with a delay of about one update
// interval (`--pose-delay`, default 0.1 s) the samples after τ have normally arrived and pings
// are interpolated; the rendered pose then lags the vehicle by the delay. A delay of 0 has no
// lag and extrapolates every ping.
#include <array>
#include <cstdint>
#include <optional>

namespace sonarloop::emulator {

// Samples kept per part of the pose: 1.6 s at 10 Hz, enough for any delay up to the stale limit
// a sender that keeps its rate can meet.
inline constexpr int kPoseHistorySamples = 16;
// Relaxation of the stamp-to-clock offset (minimum-delay filter): 100 ppm.
inline constexpr double kOffsetRelaxPerSecond = 1e-4;

// One part of the pose: N values per sample (position: north, east; attitude: pitch, roll).
template <int N>
struct PartSample {
  std::int64_t t_ns = 0;  // on the emulator's clock
  std::array<double, N> v{};
};

template <int N>
struct PartValue {
  std::array<double, N> v{};
  bool extrapolated = false;  // τ was after the last sample
};

// The samples of one part, oldest first, at most kPoseHistorySamples. Not thread-safe.
template <int N>
class PartTrack {
 public:
  // `angular`: value 0 is an angle in radians, interpolated along the shorter way round and
  // wrapped to [0, 2π).
  explicit PartTrack(bool angular = false) : angular_(angular) {}

  // Adds a sample. A sample older than the newest is dropped (false); one at the newest time
  // replaces it.
  bool add(std::int64_t t_ns, const std::array<double, N>& v);
  // The part became unknown (e.g. NaN in a UDP snapshot): forget its samples.
  void clear() { count_ = 0; }
  bool empty() const { return count_ == 0; }
  int size() const { return count_; }
  const PartSample<N>& newest() const { return at(count_ - 1); }

  // The value at τ by the rule above; nullopt when empty.
  std::optional<PartValue<N>> value_at(std::int64_t tau_ns,
                                       std::int64_t max_extrapolation_ns) const;

 private:
  const PartSample<N>& at(int i) const {
    return ring_[static_cast<std::size_t>((head_ + i) % kPoseHistorySamples)];
  }
  std::array<double, N> blend(const PartSample<N>& a, const PartSample<N>& b,
                              double fraction) const;

  bool angular_;
  std::array<PartSample<N>, kPoseHistorySamples> ring_{};
  int head_ = 0;  // index of the oldest
  int count_ = 0;
};

// The sender's stamps -> the emulator's clock (minimum-delay filter, see above).
class StampClock {
 public:
  // The emulator-clock time of a sample stamped `stamp_ns` (sender clock) that arrived at
  // `arrival_ns` (emulator clock). Never later than its arrival.
  std::int64_t place(std::int64_t stamp_ns, std::int64_t arrival_ns);

 private:
  bool have_ = false;
  double offset_ns_ = 0.0;  // arrival - stamp, minimum-filtered
  std::int64_t last_arrival_ns_ = 0;
};

// Angle difference b - a wrapped to (-π, π].
double shortest_turn_rad(double a, double b);

extern template class PartTrack<1>;
extern template class PartTrack<2>;

}  // namespace sonarloop::emulator
