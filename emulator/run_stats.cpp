#include "emulator/run_stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "drivers/json/json_writer.h"

namespace sonarloop::emulator {

// ---- LatencyHistogram ----

int LatencyHistogram::bucket_of(std::int64_t ns) {
  if (ns < kMinNs) return 0;
  if (ns >= kMaxNs) return kBuckets - 1;
  const double decades = std::log10(static_cast<double>(ns) / static_cast<double>(kMinNs));
  const int b = 1 + static_cast<int>(std::floor(decades * kBucketsPerDecade));
  return std::clamp(b, 1, kBuckets - 2);
}

double LatencyHistogram::bucket_lower_ns(int bucket) {
  if (bucket <= 0) return 0.0;
  if (bucket >= kBuckets - 1) return static_cast<double>(kMaxNs);
  return static_cast<double>(kMinNs) *
         std::pow(10.0, static_cast<double>(bucket - 1) / kBucketsPerDecade);
}

void LatencyHistogram::add(std::int64_t ns) {
  ns = std::max<std::int64_t>(ns, 0);
  ++buckets_[static_cast<std::size_t>(bucket_of(ns))];
  if (count_ == 0) {
    min_ns_ = max_ns_ = ns;
  } else {
    min_ns_ = std::min(min_ns_, ns);
    max_ns_ = std::max(max_ns_, ns);
  }
  ++count_;
  sum_ns_ += static_cast<double>(ns);
}

void LatencyHistogram::merge(const LatencyHistogram& other) {
  if (other.count_ == 0) return;
  for (std::size_t i = 0; i < buckets_.size(); ++i)
    buckets_[i] += other.buckets_[i];
  if (count_ == 0) {
    min_ns_ = other.min_ns_;
    max_ns_ = other.max_ns_;
  } else {
    min_ns_ = std::min(min_ns_, other.min_ns_);
    max_ns_ = std::max(max_ns_, other.max_ns_);
  }
  count_ += other.count_;
  sum_ns_ += other.sum_ns_;
}

double LatencyHistogram::mean_ns() const {
  return count_ ? sum_ns_ / static_cast<double>(count_) : 0.0;
}

double LatencyHistogram::quantile_ns(double q) const {
  if (count_ == 0) return 0.0;
  q = std::clamp(q, 0.0, 1.0);
  // the rank-th smallest value (1-based, nearest rank)
  const auto rank = std::max<std::uint64_t>(
      1, static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(count_))));
  std::uint64_t seen = 0;
  int b = 0;
  for (; b < kBuckets; ++b) {
    seen += buckets_[static_cast<std::size_t>(b)];
    if (seen >= rank) break;
  }
  double v;
  if (b == 0) {
    v = 0.5 * static_cast<double>(kMinNs);
  } else if (b >= kBuckets - 1) {
    v = static_cast<double>(max_ns_);
  } else {
    v = std::sqrt(bucket_lower_ns(b) * bucket_lower_ns(b + 1));  // geometric centre
  }
  return std::clamp(v, static_cast<double>(min_ns_), static_cast<double>(max_ns_));
}

// ---- formatting ----

namespace {
double ms(double ns) {
  return ns * 1e-6;
}
}  // namespace

void format_stats_line(const RunStats& s, char* out, std::size_t out_size) {
  if (out_size == 0) return;
  int n = std::snprintf(out, out_size,
                        "t %.1f s | pings %llu sent, %llu missed (%llu late, %llu dropped)",
                        s.sim_time_s, static_cast<unsigned long long>(s.pings_sent),
                        static_cast<unsigned long long>(s.deadline_misses()),
                        static_cast<unsigned long long>(s.pings_late),
                        static_cast<unsigned long long>(s.pings_dropped));
  auto append = [&](const char* fmt, auto... args) {
    if (n < 0 || static_cast<std::size_t>(n) >= out_size) return;
    const int m = std::snprintf(out + n, out_size - static_cast<std::size_t>(n), fmt, args...);
    if (m > 0) n += m;
  };
  if (s.pings_stale) append(", %llu stale", static_cast<unsigned long long>(s.pings_stale));
  if (s.pings_extrapolated) {
    append(", %llu extrapolated", static_cast<unsigned long long>(s.pings_extrapolated));
  }
  if (s.ping_lateness.count()) {
    append(" | lateness p50 %.3f p99 %.3f max %.3f ms", ms(s.ping_lateness.quantile_ns(0.5)),
           ms(s.ping_lateness.quantile_ns(0.99)),
           ms(static_cast<double>(s.ping_lateness.max_ns())));
  } else if (s.rate == "max" && s.wall_time_s > 0) {
    append(" | %.1f pings/s (%.1fx real time)", static_cast<double>(s.pings_sent) / s.wall_time_s,
           s.sim_time_s / s.wall_time_s);
  }
  append(" | nav %llu frames", static_cast<unsigned long long>(s.nav_frames));
  if (s.nav_frames_withheld) {
    append(" (%llu withheld)", static_cast<unsigned long long>(s.nav_frames_withheld));
  }
  append(" | render %.2f ms/ping", s.render_mean_ms);
  if (s.udp_dropped)
    append(" | udp %llu refused/dropped", static_cast<unsigned long long>(s.udp_dropped));
  append(" | cpu %.0f %%", s.cpu_percent());
}

std::string stats_json(const RunStats& s) {
  json::Writer w(true);
  auto hist = [&](const char* name, const LatencyHistogram& h) {
    w.key(name).begin_object();
    w.field("count", h.count());
    w.field("p50_ms", ms(h.quantile_ns(0.5)), 6);
    w.field("p99_ms", ms(h.quantile_ns(0.99)), 6);
    w.field("max_ms", ms(static_cast<double>(h.max_ns())), 6);
    w.field("mean_ms", ms(h.mean_ns()), 6);
    w.end_object();
  };
  w.begin_object();
  w.field("rate", s.rate).field("threads", s.threads).field("ring_slots", s.ring_slots);
  w.field("realtime", s.realtime);
  w.field("ping_period_s", s.ping_period_s, 9).field("send_delay_s", s.send_delay_s, 9);
  w.field("bins_per_side", s.bins_per_side).field("bin_size_m", s.bin_size_m, 6);
  w.field("max_range_m", s.max_range_m, 6).field("packet_bytes", s.packet_bytes);
  w.field("epoch_utc_ns", s.epoch_utc_ns);
  w.field("sim_time_s", s.sim_time_s, 9).field("wall_time_s", s.wall_time_s, 6);
  w.field("cpu_time_s", s.cpu_time_s, 6).field("cpu_percent", s.cpu_percent(), 4);
  w.field("startup_s", s.startup_s, 6);
  w.key("pings").begin_object();
  w.field("due", s.pings_due).field("sent", s.pings_sent).field("late", s.pings_late);
  w.field("late_render", s.pings_late_render);
  w.field("dropped", s.pings_dropped).field("stale", s.pings_stale);
  w.field("stale_episodes", s.stale_episodes);
  w.field("extrapolated", s.pings_extrapolated);
  w.field("deadline_misses", s.deadline_misses());
  w.field("deadline_tolerance_ms", ms(static_cast<double>(s.deadline_tolerance_ns)), 6);
  w.field("rendered", s.pings_rendered).field("abandoned", s.pings_abandoned);
  w.field("pings_per_wall_s",
          s.wall_time_s > 0 ? static_cast<double>(s.pings_sent) / s.wall_time_s : 0.0, 6);
  w.field("render_mean_ms", s.render_mean_ms, 6).field("render_max_ms", s.render_max_ms, 6);
  hist("lateness", s.ping_lateness);
  hist("latency", s.ping_latency);
  w.end_object();
  if (s.has_pose_source) {
    w.key("pose_source").begin_object();
    w.field("updates", s.pose_updates).field("rejected", s.pose_rejected);
    w.field("reanchors", s.pose_reanchors).field("malformed", s.pose_malformed);
    w.field("lost", s.pose_lost).field("sender_restarts", s.pose_restarts);
    w.end_object();
  }
  w.key("nav").begin_object();
  w.field("samples", s.nav_samples).field("frames", s.nav_frames);
  w.field("skipped", s.nav_frames_skipped).field("withheld", s.nav_frames_withheld);
  hist("lateness", s.nav_lateness);
  w.end_object();
  w.key("udp").begin_object();
  w.field("datagrams", s.udp_datagrams).field("header_datagrams", s.udp_header_datagrams);
  w.field("dropped", s.udp_dropped).field("bytes", s.udp_bytes);
  w.end_object();
  if (s.imc_datagrams) {
    w.key("imc").begin_object();
    w.field("datagrams", s.imc_datagrams).field("dropped", s.imc_dropped);
    w.field("bytes", s.imc_bytes);
    w.end_object();
  }
  w.field("recorded_pings", s.recorded_pings);
  if (s.mcap_messages || !s.mcap_error.empty()) w.field("mcap_messages", s.mcap_messages);
  w.key("scene").begin_object();
  w.field("tiles_made", s.tiles_made);
  const seabed::SeabedCacheStats& c = s.seabed_cache;
  w.key("cache").begin_object();
  w.field("heightmap_hits", c.heightmap.hits).field("heightmap_misses", c.heightmap.misses);
  w.field("noise_hits", c.noise.hits).field("noise_misses", c.noise.misses);
  w.field("evictions", c.heightmap.evictions + c.noise.evictions);
  w.field("bytes", static_cast<std::uint64_t>(c.bytes));
  w.field("budget_bytes", static_cast<std::uint64_t>(c.budget_bytes));
  w.end_object();
  w.end_object();
  w.end_object();
  return w.str();
}

}  // namespace sonarloop::emulator
