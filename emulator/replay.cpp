#include "emulator/replay.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "drivers/can/candump_log.h"
#include "drivers/xtf/xtf_file.h"
#include "emulator/stderr_warning.h"

namespace sonarloop::emulator {
namespace {

// Longest single sleep while waiting for a deadline, so that a stop request (SIGINT, which may be
// delivered to another thread and not interrupt the sleep) is seen within this time.
constexpr std::int64_t kStopPollNs = 50'000'000;

bool stop_requested(const ReplayOptions& o) {
  return o.stop && o.stop->load(std::memory_order_relaxed);
}

// Absolute-deadline pacing against the clock, and the counters that go with it.
class Pacing {
 public:
  Pacing(Clock& clock, const ReplayOptions& options, ReplaySummary& summary)
      : clock_(clock), options_(options), summary_(summary), start_ns_(clock.now_ns()) {
    last_progress_ns_ = start_ns_;
  }

  // Waits until the deadline of recording time t_ns (from the start of the replay, across
  // passes). measure: count the lateness of this send. false if stopped.
  bool wait(std::int64_t t_ns, bool measure = true) {
    if (stop_requested(options_)) return false;
    if (options_.rate.max) return true;
    const std::int64_t deadline =
        start_ns_ + std::llround(static_cast<double>(t_ns) / options_.rate.factor);
    for (;;) {
      const std::int64_t now = clock_.now_ns();
      if (now >= deadline) {
        if (measure) {
          const std::int64_t late = now - deadline;
          ++summary_.paced_sends;
          summary_.total_late_ns += late;
          summary_.max_late_ns = std::max(summary_.max_late_ns, late);
        }
        return true;
      }
      if (stop_requested(options_)) return false;
      clock_.sleep_until(std::min(deadline, now + kStopPollNs));
    }
  }

  // After each send: wall time and progress.
  void sent() {
    const std::int64_t now = clock_.now_ns();
    summary_.wall_ns = now - start_ns_;
    if (options_.on_progress && now - last_progress_ns_ >= options_.progress_period_ns) {
      last_progress_ns_ = now;
      options_.on_progress(summary_);
    }
  }

 private:
  Clock& clock_;
  const ReplayOptions& options_;
  ReplaySummary& summary_;
  std::int64_t start_ns_;
  std::int64_t last_progress_ns_;
};

std::int64_t median(std::vector<std::int64_t> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2 == 1) return *mid;
  const std::int64_t hi = *mid;
  const std::int64_t lo = *std::max_element(v.begin(), mid);
  return lo + (hi - lo) / 2;
}

}  // namespace

// ---- rate ----

ReplayRate parse_replay_rate(const std::string& text) {
  ReplayRate r;
  if (text == "original" || text == "realtime") return r;
  if (text == "max") {
    r.max = true;
    return r;
  }
  char* end = nullptr;
  errno = 0;
  const double f = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno != 0 || !std::isfinite(f) ||
      f < kMinReplayRate || f > kMaxReplayRate) {
    char range[96];
    std::snprintf(range, sizeof range, "a speed factor in [%g, %g] (2 = twice as fast)",
                  kMinReplayRate, kMaxReplayRate);
    throw std::invalid_argument("--rate '" + text + "': expected original, max or " + range);
  }
  r.factor = f;
  return r;
}

std::string to_string(const ReplayRate& rate) {
  if (rate.max) return "max";
  if (rate.factor == 1.0) return "original";
  char text[32];
  std::snprintf(text, sizeof text, "x%g", rate.factor);
  return text;
}

// ---- XTF schedule ----

XtfSchedule make_xtf_schedule(std::span<const XtfPacketTime> packets) {
  XtfSchedule s;
  s.t_ns.assign(packets.size(), 0);

  // the pings, with their recorded times
  std::vector<std::size_t> ping_index;
  for (std::size_t i = 0; i < packets.size(); ++i) {
    if (packets[i].is_ping) ping_index.push_back(i);
  }
  const std::size_t n = ping_index.size();
  s.pings = n;
  auto time_of = [&](std::size_t j) { return packets[ping_index[j]].time_utc_ns; };

  // segments: maximal runs of pings with valid, non-decreasing times. Inside a segment each ping
  // gets an "interpolated" time: runs of equal times are spread up to the next later time; the
  // pings of a run that ends the segment stay unknown (nullopt) except the run's first
  std::vector<bool> starts_segment(n, false);
  std::vector<std::optional<std::int64_t>> interp(n);
  for (std::size_t j = 0; j < n; ++j) {
    starts_segment[j] = j == 0 || !time_of(j) || !time_of(j - 1) || *time_of(j) < *time_of(j - 1);
    if (!time_of(j)) {
      if (s.invalid_times++ == 0) s.first_invalid_time = ping_index[j];
    } else if (j > 0 && time_of(j - 1) && *time_of(j) - *time_of(j - 1) > kMaxPingGapNs) {
      // an implausible jump forward: not waited for
      starts_segment[j] = true;
      if (s.time_jumps++ == 0) s.first_time_jump = ping_index[j];
    }
  }
  for (std::size_t j = 0; j < n;) {
    if (!time_of(j)) {
      ++j;
      continue;
    }
    // the run of pings at the same time as j, within j's segment
    std::size_t k = j + 1;
    while (k < n && !starts_segment[k] && *time_of(k) == *time_of(j))
      ++k;
    const std::int64_t t0 = *time_of(j);
    interp[j] = t0;
    if (k < n && !starts_segment[k]) {
      // spread the run evenly over [t0, next later time)
      const std::int64_t step_total = *time_of(k) - t0;
      const auto run = static_cast<std::int64_t>(k - j);
      for (std::size_t m = j + 1; m < k; ++m) {
        interp[m] = t0 + step_total * static_cast<std::int64_t>(m - j) / run;
        ++s.spread_pings;
      }
    }
    j = k;
  }

  // the file's typical interval: the median of its increasing steps
  std::vector<std::int64_t> steps;
  for (std::size_t j = 1; j < n; ++j) {
    if (!starts_segment[j] && interp[j] && interp[j - 1] && *interp[j] > *interp[j - 1])
      steps.push_back(*interp[j] - *interp[j - 1]);
  }
  std::optional<std::int64_t> file_interval;
  if (!steps.empty()) file_interval = median(steps);
  if (!file_interval) {
    for (std::size_t j = 0; j < n; ++j) {
      const double spp = packets[ping_index[j]].seconds_per_ping_s;
      if (std::isfinite(spp) && spp > 0.0) {
        file_interval = std::llround(spp * 1e9);
        break;
      }
    }
  }
  s.fallback_interval_ns = file_interval.value_or(kDefaultPingIntervalNs);
  // the interval after ping j when its recorded time cannot be used
  auto fallback_after = [&](std::size_t j) {
    const double spp = packets[ping_index[j]].seconds_per_ping_s;
    if (std::isfinite(spp) && spp > 0.0) return std::max<std::int64_t>(1, std::llround(spp * 1e9));
    return s.fallback_interval_ns;
  };

  // ping times: recorded steps where known, fallback steps elsewhere
  std::vector<std::int64_t> ping_t(n, 0);
  for (std::size_t j = 1; j < n; ++j) {
    if (!starts_segment[j] && interp[j] && interp[j - 1]) {
      ping_t[j] = ping_t[j - 1] + (*interp[j] - *interp[j - 1]);
    } else {
      ping_t[j] = ping_t[j - 1] + fallback_after(j);
      ++s.fallback_pings;
    }
  }

  // every packet: its ping's time, or the time of the ping before it (0 before the first)
  std::int64_t current = 0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < packets.size(); ++i) {
    if (packets[i].is_ping) current = ping_t[j++];
    s.t_ns[i] = current;
  }
  s.span_ns = packets.empty() ? 0 : s.t_ns.back();
  s.pass_period_ns = s.span_ns + s.fallback_interval_ns;
  return s;
}

XtfTimeline read_xtf_timeline(const std::string& path, std::uint64_t skip_larger_than) {
  xtf::XtfReader reader(path);
  reader.skip_larger_than(skip_larger_than);
  XtfTimeline tl;
  tl.file_header = reader.file_header_bytes();
  std::vector<XtfPacketTime> times;
  xtf::XtfRecord record;
  while (reader.next(record)) {
    XtfPacketTime t;
    t.is_ping = record.is_ping;
    if (record.is_ping) {
      t.time_utc_ns = xtf::time_utc_ns(record.ping.header);
      if (!record.ping.channels.empty())
        t.seconds_per_ping_s = record.ping.channels.front().seconds_per_ping_s;
    }
    times.push_back(t);
    tl.packet_bytes.push_back(record.packet.record_bytes);
    tl.packet_offsets.push_back(record.packet.offset);
  }
  tl.schedule = make_xtf_schedule(times);
  return tl;
}

// ---- XTF replay ----

ReplaySummary replay_xtf(const std::string& path, const DatagramSink& send, Clock& clock,
                         const ReplayOptions& options_in) {
  ReplayOptions options = options_in;
  if (!options.on_warning) options.on_warning = warn_on_stderr;
  // a packet too long for one datagram is skipped by seeking, never read
  const XtfTimeline tl = read_xtf_timeline(path, options.max_datagram_bytes);
  const XtfSchedule& sched = tl.schedule;
  const std::size_t n = tl.packet_bytes.size();

  if (sched.first_time_jump) {
    options.on_warning(
        "'" + path + "': the ping at byte offset " +
        std::to_string(tl.packet_offsets[*sched.first_time_jump]) + " is more than " +
        std::to_string(kMaxPingGapNs / 1'000'000'000) +
        " s after the ping before it (a corrupt date?): not waited for, paced by the ping "
        "period instead (" +
        std::to_string(sched.time_jumps) + " such ping" + (sched.time_jumps == 1 ? "" : "s") +
        " in the file)");
  }
  if (sched.first_invalid_time) {
    options.on_warning("'" + path + "': the ping at byte offset " +
                       std::to_string(tl.packet_offsets[*sched.first_invalid_time]) +
                       " has invalid date fields: paced by the ping period (" +
                       std::to_string(sched.invalid_times) + " such ping" +
                       (sched.invalid_times == 1 ? "" : "s") + " in the file)");
  }

  ReplaySummary summary;
  summary.packets_per_pass = n;
  summary.recording_span_ns = sched.span_ns;
  Pacing pacing(clock, options, summary);
  bool warned_drop = false;
  auto send_counted = [&](std::span<const std::uint8_t> datagram) {
    const bool ok = send(datagram);
    if (!ok) {
      ++summary.dropped;
      if (!warned_drop) {
        options.on_warning(
            "a datagram was dropped (refused by the destination: is anything "
            "listening? or the kernel queue was full); further drops are counted");
        warned_drop = true;
      }
    }
    summary.bytes_sent += datagram.size();
    return ok;
  };

  // an empty file (header only) is one pass whatever the loop count
  const std::uint64_t passes = n == 0 ? 1 : options.loops;
  xtf::XtfRawPacket packet;
  for (std::uint64_t pass = 0; passes == 0 || pass < passes; ++pass) {
    summary.pass = pass;
    const std::int64_t base = static_cast<std::int64_t>(pass) * sched.pass_period_ns;
    if (!pacing.wait(base, false)) {
      summary.stopped = true;
      return summary;
    }
    send_counted(tl.file_header);
    ++summary.file_headers_sent;
    pacing.sent();
    std::int64_t header_t = 0;

    xtf::XtfReader reader(path);
    reader.skip_larger_than(options.max_datagram_bytes);
    for (std::size_t k = 0; k < n; ++k) {
      if (!reader.next_raw(packet) || packet.record_bytes != tl.packet_bytes[k]) {
        throw std::runtime_error("'" + path + "' changed during the replay (packet " +
                                 std::to_string(k) + " at byte offset " +
                                 std::to_string(reader.offset()) + ")");
      }
      const std::int64_t t = sched.t_ns[k];
      if (!pacing.wait(base + t)) {
        summary.stopped = true;
        return summary;
      }
      if (options.file_header_period_ns > 0 && t - header_t >= options.file_header_period_ns) {
        send_counted(tl.file_header);
        ++summary.file_headers_sent;
        header_t = t;
      }
      if (packet.skipped) {
        if (summary.skipped++ == 0) {
          options.on_warning("'" + path + "': packet at byte offset " +
                             std::to_string(packet.offset) + " has " +
                             std::to_string(packet.record_bytes) + " bytes, more than one " +
                             std::to_string(options.max_datagram_bytes) +
                             "-byte datagram: skipped (further ones are counted)");
        }
        continue;
      }
      send_counted(packet.bytes);
      ++summary.packets_sent;
      if (packet.header_type == xtf::kHeaderTypeSonar) ++summary.pings_sent;
      summary.recording_position_ns = t;
      pacing.sent();
    }
    ++summary.passes_completed;
  }
  return summary;
}

// ---- candump replay ----

ReplaySummary replay_candump(const std::string& path,
                             std::span<can::CanTransport* const> transports, Clock& clock,
                             const ReplayOptions& options_in) {
  ReplayOptions options = options_in;
  if (!options.on_warning) options.on_warning = warn_on_stderr;

  // first pass: every line checked, the time span measured
  std::uint64_t records = 0;
  std::int64_t first_t = 0;
  std::int64_t last_t = 0;
  {
    can::CandumpReader reader(path, true, true);
    while (const auto rec = reader.next()) {
      if (records == 0) first_t = last_t = rec->t_ns;
      last_t = std::max(last_t, rec->t_ns);
      ++records;
    }
    if (reader.torn_tail() != 0) {
      options.on_warning(path + ":" + std::to_string(reader.torn_tail()) +
                         ": the last line has no newline (a write torn by a crash or a full "
                         "disk): ignored");
    }
  }
  ReplaySummary summary;
  summary.packets_per_pass = records;
  summary.recording_span_ns = last_t - first_t;
  Pacing pacing(clock, options, summary);

  const std::uint64_t passes = records == 0 ? 1 : options.loops;
  for (std::uint64_t pass = 0; passes == 0 || pass < passes; ++pass) {
    summary.pass = pass;
    const std::int64_t base = static_cast<std::int64_t>(pass) * summary.recording_span_ns;
    can::CandumpReader reader(path, true, true);
    std::int64_t previous_t = first_t;
    while (const auto rec = reader.next()) {
      const bool in_order = rec->t_ns >= previous_t;
      if (!in_order) ++summary.out_of_order;
      previous_t = rec->t_ns;
      const std::int64_t t = rec->t_ns - first_t;
      if (!pacing.wait(base + t, in_order)) {
        summary.stopped = true;
        return summary;
      }
      if (rec->kind != can::CandumpFrameKind::kData) {
        if (summary.skipped++ == 0) {
          options.on_warning(path + ":" + std::to_string(reader.line_number()) +
                             ": remote, error and CAN FD frames cannot be replayed to the CAN "
                             "transports: skipped (further ones are counted)");
        }
        continue;
      }
      for (can::CanTransport* tr : transports)
        tr->send(rec->frame, rec->t_ns);
      ++summary.packets_sent;
      summary.bytes_sent += rec->frame.len;
      summary.recording_position_ns = t;
      pacing.sent();
    }
    ++summary.passes_completed;
  }
  for (can::CanTransport* tr : transports)
    tr->flush();
  return summary;
}

}  // namespace sonarloop::emulator
