#pragma once
// Replaying recordings with their original timing (`sonarloop replay`, tools/cmd_replay.cpp):
//
//   replay_xtf      an XTF file (ours, or a real one) as the live sonar stream: the file header
//                   as one datagram first, then every packet of the file as one datagram, byte
//                   for byte, paced by the pings' times. "File header + the packet datagrams" is
//                   the file again (docs/design.md, "Wire conventions").
//   replay_candump  a candump log to CAN transports (SocketCAN, socketcand, log files), each
//                   frame at its logged time relative to the first, as can-utils' canplayer does.
//
// Pacing uses absolute deadlines, deadline(k) = start + (t_k - t_0) / rate, so lateness never
// accumulates: a late frame is sent at once and the next one keeps its own deadline.
//
// Clock. replay_xtf(), replay_candump() and the `replay` command read the time and wait only
// through the emulator's Clock (emulator/pacer.h), the same interface the run loop uses. The real
// one (MonotonicClock) reads CLOCK_MONOTONIC and sleeps with clock_nanosleep(TIMER_ABSTIME); tests
// pass a simulated clock (tests/emulator/simulated_clock.h) and check the deadlines exactly.
//
// XTF timing (make_xtf_schedule). A ping's time is its header's Year..HSeconds (1/100 s
// resolution, xtf::time_utc_ns). Relative times are kept as recorded wherever they increase.
// Where they do not:
//   * equal times (several pings in one hundredth, or a fast sonar logged coarsely): the run of
//     equal-time pings is spread evenly up to the next later time; a run at the end of the file
//     steps by the fallback interval;
//   * a time earlier than the previous ping's (clock stepped back) or a missing/invalid time: the
//     ping follows the previous one after the fallback interval, and the recorded times count
//     again from there (a discontinuity: later pings keep their recorded spacing);
//   * a time more than kMaxPingGapNs after the previous ping's (a corrupt year, say, which once
//     made `replay --rate 10` wait 197 years): treated as a discontinuity too, as is the step
//     back from it; replay_xtf warns once, naming the byte offset of the first such ping, and
//     once for the first ping with invalid date fields (month 13, hour 25, ...);
//   * the fallback interval is the ping's own SecondsPerPing (first channel) if > 0, else the
//     median of the file's increasing ping intervals (after spreading equal runs), else
//     kDefaultPingIntervalNs.
// Non-sonar packets (attitude, navigation, ...) carry no common time field: they are sent as
// recorded, right after the ping before them (at time 0 before the first ping), so the stream
// stays the file. Packets larger than max_datagram_bytes cannot be one UDP datagram: they are
// skipped, counted and reported.
// The file header is sent before the first packet of each pass and again whenever
// file_header_period_ns of recording time has passed since it was last sent (so a receiver that
// joins late can start; at any rate the receiver sees it every period of recording time).
//
// candump timing: frames are sent at their logged times relative to the first frame. A frame
// logged earlier than the one before it has a deadline in the past and is sent at once (as
// canplayer does); it is counted as out of order. Remote, error and CAN FD frames cannot be
// carried by the CAN transports (classic data frames only): they are skipped and counted. The
// frames keep their logged timestamps (a log:FILE transport writes them, a socketcand server
// sends them) and go to every transport regardless of the log's channel name.
//
// Loops: options.loops passes over the file (0 = until stopped). An XTF pass starts one fallback
// interval after the last ping of the previous pass; a candump pass starts right after the last
// frame of the previous one (as canplayer -l does).
//
// Errors: the whole file is read once before anything is sent, so a truncated or corrupt XTF
// file (xtf::XtfFormatError, with the byte offset) or a malformed candump line (std::runtime_error
// "FILE:LINE: what") stops the replay before its first packet; a missing file throws
// std::runtime_error naming it. The one exception: a candump log's last line without its newline
// (torn by a crash or a full disk) is ignored with a warning naming its line, and the whole
// lines before it are replayed.
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "drivers/can/can_transport.h"
#include "drivers/net/udp_sender.h"
#include "drivers/xtf/xtf_file.h"
#include "emulator/pacer.h"

namespace sonarloop::emulator {

// ---- options and results ----

// --rate: original (recorded timing), max (no waiting) or a speed factor (2 = twice as fast).
struct ReplayRate {
  bool max = false;
  double factor = 1.0;  // > 0; ignored when max
};
// Parses "original" (or "realtime"), "max" or a number in [kMinReplayRate, kMaxReplayRate].
// Throws std::invalid_argument naming the text and what is allowed.
ReplayRate parse_replay_rate(const std::string& text);
inline constexpr double kMinReplayRate = 1e-3;
inline constexpr double kMaxReplayRate = 1e6;
std::string to_string(const ReplayRate& rate);

// Fallback ping interval when a file gives no usable timing at all: 0.1 s, the ping period of a
// sidescan at 75 m range (2·75 m / 1500 m/s = 0.1 s), a common survey setting.
inline constexpr std::int64_t kDefaultPingIntervalNs = 100'000'000;

// Largest step forward between two pings' recorded times that replay waits for: 60 s, six times
// the longest ping period a sonar may have (config: ping_period_s <= 10 s). A longer step is a
// corrupt date or a paused logger; replaying it would only stall the stream.
inline constexpr std::int64_t kMaxPingGapNs = 60'000'000'000;

struct ReplaySummary;

struct ReplayOptions {
  ReplayRate rate;
  std::uint64_t loops = 1;  // passes over the file; 0 = until stopped
  // XTF: re-send the file header after this much recording time (<= 0: only at pass starts).
  std::int64_t file_header_period_ns = 1'000'000'000;
  // XTF: larger packets are skipped (they cannot be one datagram).
  std::size_t max_datagram_bytes = net::kMaxUdpDatagramBytes;
  // Set from another thread or a signal handler to stop after the current packet.
  const std::atomic<bool>* stop = nullptr;
  // Called every progress_period_ns of wall time (by the clock) with the counts so far.
  std::function<void(const ReplaySummary&)> on_progress;
  std::int64_t progress_period_ns = 5'000'000'000;
  // Called for conditions worth a line (skipped packets, first dropped datagram). Default: a
  // "warning: ..." line on stderr.
  std::function<void(const std::string&)> on_warning;
};

struct ReplaySummary {
  std::uint64_t packets_per_pass = 0;  // packets (XTF) or frames (candump) in the file
  std::int64_t recording_span_ns = 0;  // time from the first to the last packet of one pass
  std::uint64_t pass = 0;              // current pass (0-based)
  std::uint64_t passes_completed = 0;
  std::uint64_t packets_sent = 0;          // XTF packets / CAN frames sent (once per frame)
  std::uint64_t pings_sent = 0;            // XTF sonar pings among packets_sent
  std::uint64_t file_headers_sent = 0;     // XTF
  std::uint64_t bytes_sent = 0;            // datagram bytes incl. file headers / CAN data bytes
  std::uint64_t dropped = 0;               // datagrams the sender reported dropped (refused, full)
  std::uint64_t skipped = 0;               // not sendable: oversized / remote, error, FD frames
  std::uint64_t out_of_order = 0;          // candump: frames logged earlier than their predecessor
  std::int64_t recording_position_ns = 0;  // recording time of the last packet sent (this pass)
  std::int64_t wall_ns = 0;                // from the start to the last send
  // Lateness of paced sends (send time - deadline; not measured at --rate max), ns.
  std::uint64_t paced_sends = 0;
  std::int64_t max_late_ns = 0;
  std::int64_t total_late_ns = 0;
  bool stopped = false;  // ended by options.stop
};

// ---- XTF ----

// What make_xtf_schedule needs to know of each packet of a file, in file order.
struct XtfPacketTime {
  bool is_ping = false;
  std::optional<std::int64_t> time_utc_ns;  // pings: header time, nullopt if invalid
  double seconds_per_ping_s = 0.0;          // pings: first channel's SecondsPerPing, 0 = unknown
};

struct XtfSchedule {
  std::vector<std::int64_t> t_ns;  // per packet: recording time from the first ping, ns
  std::int64_t fallback_interval_ns = kDefaultPingIntervalNs;
  std::int64_t span_ns = 0;         // t_ns of the last packet
  std::int64_t pass_period_ns = 0;  // span + the interval after the last ping (loops)
  std::size_t pings = 0;
  std::size_t spread_pings = 0;    // equal-time pings spread evenly
  std::size_t fallback_pings = 0;  // pings placed by the fallback interval (after the first)
  std::size_t time_jumps = 0;      // pings more than kMaxPingGapNs after the previous one
  std::size_t invalid_times = 0;   // pings whose date fields are invalid (no time)
  std::optional<std::size_t> first_time_jump;     // packet index of the first such ping
  std::optional<std::size_t> first_invalid_time;  // packet index of the first such ping
};

// The recording time of every packet (see the header comment). Pure.
XtfSchedule make_xtf_schedule(std::span<const XtfPacketTime> packets);

// Reads and checks the whole file (every ping decoded, but those skipped) and returns its file
// header bytes and schedule. Throws xtf::XtfFormatError (offset) or std::runtime_error (cannot
// open).
struct XtfTimeline {
  std::vector<std::uint8_t> file_header;
  std::vector<std::uint64_t> packet_bytes;    // size of each packet
  std::vector<std::uint64_t> packet_offsets;  // byte offset of each packet in the file
  XtfSchedule schedule;
};
// Packets longer than skip_larger_than are not read (their length is kept; replay skips them).
XtfTimeline read_xtf_timeline(const std::string& path,
                              std::uint64_t skip_larger_than = xtf::kMaxXtfRecordBytes);

// Sends one datagram; false if it was dropped (counted).
using DatagramSink = std::function<bool(std::span<const std::uint8_t>)>;

// Replays `path` into `send` (see the header comment). Returns the summary at the end, or when
// options.stop was set.
ReplaySummary replay_xtf(const std::string& path, const DatagramSink& send, Clock& clock,
                         const ReplayOptions& options = {});

// ---- candump ----

// Replays `path` to every transport (see the header comment).
ReplaySummary replay_candump(const std::string& path,
                             std::span<can::CanTransport* const> transports, Clock& clock,
                             const ReplayOptions& options = {});

}  // namespace sonarloop::emulator
