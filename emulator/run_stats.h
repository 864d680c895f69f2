#pragma once
// Statistics of an emulator run: counters, and fixed-size latency histograms that give
// percentiles without storing samples (no allocation per ping).
//
// LatencyHistogram: log-spaced buckets, kBucketsPerDecade per decade from kMinNs (1 us) to kMaxNs
// (1000 s), plus one bucket below and one above. A percentile is reported as the geometric
// centre of its bucket, clamped to the observed minimum and maximum: relative error at most
// 10^(1/(2·20)) - 1 = 5.9 % for values inside the range. min, max, count and mean are exact.
#include <array>
#include <cstdint>
#include <string>

#include "sim/seabed/tile_cache.h"

namespace sonarloop::emulator {

class LatencyHistogram {
 public:
  static constexpr std::int64_t kMinNs = 1'000;              // 1 us
  static constexpr std::int64_t kMaxNs = 1'000'000'000'000;  // 1000 s
  static constexpr int kBucketsPerDecade = 20;
  static constexpr int kDecades = 9;                                 // 1 us .. 1000 s
  static constexpr int kBuckets = kDecades * kBucketsPerDecade + 2;  // + under, over

  // Adds one value in ns (negative values count as 0).
  void add(std::int64_t ns);
  void merge(const LatencyHistogram& other);
  void clear() { *this = LatencyHistogram{}; }

  std::uint64_t count() const { return count_; }
  std::int64_t min_ns() const { return count_ ? min_ns_ : 0; }
  std::int64_t max_ns() const { return count_ ? max_ns_ : 0; }
  double mean_ns() const;
  // The q-quantile (q in [0, 1]) in ns; 0 when empty. See the header comment for the accuracy.
  double quantile_ns(double q) const;

  // Bucket of a value, and the bucket's lower edge (for tests).
  static int bucket_of(std::int64_t ns);
  static double bucket_lower_ns(int bucket);

 private:
  std::array<std::uint64_t, kBuckets> buckets_{};
  std::uint64_t count_ = 0;
  std::int64_t min_ns_ = 0;
  std::int64_t max_ns_ = 0;
  double sum_ns_ = 0.0;
};

// A ping is a deadline miss when it is sent more than the run's tolerance after its send time
// (`run --lateness-tolerance-ms`), or not sent at all (dropped). The default, 1 ms, is 1.5 % of
// the 67 ms ping period of a 50 m sidescan and far above the scheduler's usual wake-up latency
// (tens of us).
inline constexpr std::int64_t kDefaultDeadlineToleranceNs = 1'000'000;

// Counters of one run. Written by the publisher thread, except the render counters, which the
// emulator copies in from the render queue and view cache when it prints.
struct RunStats {
  // configuration
  std::string rate;  // "realtime", "max", "2x"
  int threads = 0;
  int ring_slots = 0;
  double ping_period_s = 0.0;
  double send_delay_s = 0.0;  // ping time -> send time (the receive window)
  std::int64_t deadline_tolerance_ns = kDefaultDeadlineToleranceNs;  // late beyond this: a miss
  std::string realtime = "normal";  // the publisher's priority (realtime_priority.h summary())
  int bins_per_side = 0;
  double bin_size_m = 0.0;
  double max_range_m = 0.0;
  std::uint64_t packet_bytes = 0;  // one encoded ping
  std::int64_t epoch_utc_ns = 0;   // UTC of t = 0

  // progress
  double sim_time_s = 0.0;  // simulation time reached
  double wall_time_s = 0.0;
  double cpu_time_s = 0.0;

  // pings
  std::uint64_t pings_due = 0;   // pings whose window has come (sent + dropped + stale)
  std::uint64_t pings_sent = 0;  // published (UDP when given, recording, ...)
  std::uint64_t pings_late = 0;  // sent more than deadline_tolerance_ns late
  // of pings_late: not yet rendered when its send window opened (the render workers were late;
  // the rest woke the publisher late)
  std::uint64_t pings_late_render = 0;
  std::uint64_t pings_dropped = 0;  // not rendered before the next ping's send time
  std::uint64_t pings_stale = 0;    // not emitted: the external pose was stale (--pose-from)
  std::uint64_t stale_episodes = 0;
  std::uint64_t pings_extrapolated = 0;  // --pose-from: rendered at an extrapolated position
  // --pose-from: what the pose source counted (has_pose_source false without one)
  bool has_pose_source = false;
  std::uint64_t pose_updates = 0;    // messages / frames that updated the pose
  std::uint64_t pose_rejected = 0;   // decoded but implausible (depth, altitude, attitude, jumps)
  std::uint64_t pose_reanchors = 0;  // new reference accepted after consecutive jump rejections
  std::uint64_t pose_malformed = 0;  // undecodable
  std::uint64_t pose_lost = 0;       // UDP: missing by sequence number
  std::uint64_t pose_restarts = 0;   // UDP: sequence jumps taken as a sender restart
  LatencyHistogram ping_lateness;    // send - send deadline (paced runs)
  LatencyHistogram ping_latency;     // send - ping time (paced runs): send delay + lateness

  // navigation
  std::uint64_t nav_samples = 0;          // sample instants published (one SID each)
  std::uint64_t nav_frames = 0;           // frames put on each CAN output (per output)
  std::uint64_t nav_frames_skipped = 0;   // PGN deadlines skipped after an overrun
  std::uint64_t nav_frames_withheld = 0;  // pose PGNs not sent while the external pose was stale
  LatencyHistogram nav_lateness;

  // outputs
  std::uint64_t udp_datagrams = 0;  // ping and header datagrams handed to the kernel
  std::uint64_t udp_header_datagrams = 0;
  std::uint64_t udp_dropped = 0;  // refused or queue full (counted by the sender)
  std::uint64_t udp_bytes = 0;
  std::uint64_t imc_datagrams = 0;  // IMC packets handed to the kernel (--imc)
  std::uint64_t imc_dropped = 0;
  std::uint64_t imc_bytes = 0;
  std::uint64_t recorded_pings = 0;
  std::string recording_error;      // the write error that stopped --record ("" if none)
  std::uint64_t mcap_messages = 0;  // messages in the MCAP recording (--record, --mcap)
  std::string mcap_error;           // the error that stopped it ("" if none)

  // rendering (from the render queue and the view cache)
  std::uint64_t pings_rendered = 0;
  std::uint64_t pings_abandoned = 0;  // renders cut short: given up, or the run stopped
  double render_mean_ms = 0.0;
  double render_max_ms = 0.0;
  std::uint64_t tiles_made = 0;           // heightmap tiles the seabed made (all detail levels)
  seabed::SeabedCacheStats seabed_cache;  // its tile caches: hits, misses, bytes, budget
  double startup_s = 0.0;                 // scene, first view and outputs, before t = 0

  // deadline misses: late + dropped
  std::uint64_t deadline_misses() const { return pings_late + pings_dropped; }
  // CPU use, % of one core, over the run's wall time
  double cpu_percent() const { return wall_time_s > 0 ? 100.0 * cpu_time_s / wall_time_s : 0.0; }
};

// One line for the live display, e.g.
// "t 12.0 s | pings 180 sent, 0 missed (0 late, 0 dropped) | lateness p50 0.06 p99 0.21 max
//  0.40 ms | nav 1432 frames | render 2.7 ms/ping | cpu 11 %". Writes at most out_size bytes
// (NUL-terminated); no allocation.
void format_stats_line(const RunStats& s, char* out, std::size_t out_size);

// The whole record as a JSON object (pretty-printed), for --stats-json.
std::string stats_json(const RunStats& s);

}  // namespace sonarloop::emulator
