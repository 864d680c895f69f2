#include "emulator/pose_history.h"
#include "units/angles.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sonarloop::emulator {

double shortest_turn_rad(double a, double b) {
  const double d = wrap_to_two_pi(b - a);
  return d > std::numbers::pi ? d - 2.0 * std::numbers::pi : d;
}

template <int N>
bool PartTrack<N>::add(std::int64_t t_ns, const std::array<double, N>& v) {
  if (count_ > 0) {
    const std::int64_t newest_t = newest().t_ns;
    if (t_ns < newest_t) return false;
    if (t_ns == newest_t) {
      ring_[static_cast<std::size_t>((head_ + count_ - 1) % kPoseHistorySamples)].v = v;
      return true;
    }
  }
  if (count_ == kPoseHistorySamples) {
    head_ = (head_ + 1) % kPoseHistorySamples;
    --count_;
  }
  ring_[static_cast<std::size_t>((head_ + count_) % kPoseHistorySamples)] = PartSample<N>{t_ns, v};
  ++count_;
  return true;
}

template <int N>
std::array<double, N> PartTrack<N>::blend(const PartSample<N>& a, const PartSample<N>& b,
                                          double fraction) const {
  std::array<double, N> out{};
  for (int i = 0; i < N; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double delta = angular_ && i == 0 ? shortest_turn_rad(a.v[k], b.v[k]) : b.v[k] - a.v[k];
    out[k] = a.v[k] + fraction * delta;
  }
  if (angular_) out[0] = wrap_to_two_pi(out[0]);
  return out;
}

template <int N>
std::optional<PartValue<N>> PartTrack<N>::value_at(std::int64_t tau_ns,
                                                   std::int64_t max_extrapolation_ns) const {
  if (count_ == 0) return std::nullopt;
  const PartSample<N>& first = at(0);
  const PartSample<N>& last = newest();
  if (tau_ns <= first.t_ns) return PartValue<N>{first.v, false};
  if (tau_ns >= last.t_ns) {
    if (count_ == 1) return PartValue<N>{last.v, tau_ns > last.t_ns};
    // the last two samples' rate, carried on from the last (a blend fraction beyond 1)
    const PartSample<N>& before = at(count_ - 2);
    const std::int64_t ahead = std::min(tau_ns - last.t_ns, max_extrapolation_ns);
    const double fraction =
        1.0 + static_cast<double>(ahead) / static_cast<double>(last.t_ns - before.t_ns);
    return PartValue<N>{blend(before, last, fraction), tau_ns > last.t_ns};
  }
  // the bracketing pair: the first sample later than tau (count_ is small)
  int j = 1;
  while (at(j).t_ns <= tau_ns)
    ++j;
  const PartSample<N>& a = at(j - 1);
  const PartSample<N>& b = at(j);
  const double fraction =
      static_cast<double>(tau_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  return PartValue<N>{blend(a, b, fraction), false};
}

std::int64_t StampClock::place(std::int64_t stamp_ns, std::int64_t arrival_ns) {
  const double sample_offset = static_cast<double>(arrival_ns) - static_cast<double>(stamp_ns);
  if (!have_) {
    have_ = true;
    offset_ns_ = sample_offset;
  } else {
    const double since_s = static_cast<double>(arrival_ns - last_arrival_ns_) * 1e-9;
    offset_ns_ =
        std::min(offset_ns_ + kOffsetRelaxPerSecond * 1e9 * std::max(since_s, 0.0), sample_offset);
  }
  last_arrival_ns_ = arrival_ns;
  return std::min(arrival_ns, stamp_ns + static_cast<std::int64_t>(std::llround(offset_ns_)));
}

template class PartTrack<1>;
template class PartTrack<2>;

}  // namespace sonarloop::emulator
