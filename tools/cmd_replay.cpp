// sonarloop replay: stream an XTF recording over UDP, or a candump log to CAN transports, with
// the recorded timing (emulator/replay.h).
#include <algorithm>
#include <atomic>
#include <cctype>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "drivers/can/can_transport.h"
#include "drivers/can/candump_log.h"
#include "drivers/can/socketcand_server.h"
#include "drivers/io/input_file.h"
#include "drivers/net/host_port.h"
#include "drivers/net/udp_sender.h"
#include "emulator/pacer.h"
#include "emulator/replay.h"
#include "tools/args.h"
#include "tools/commands.h"

namespace sonarloop::tools {
namespace {

constexpr double kNsPerS = 1e9;
// After the last frame, socketcand servers stay up this long so that frames still queued for a
// slow client reach it before the connection closes.
constexpr std::int64_t kSocketcandLingerNs = 1'000'000'000;

std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

extern "C" void on_stop_signal(int) {
  g_stop.store(true, std::memory_order_relaxed);
}

void install_stop_handler() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: a sleep in the main thread wakes up
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

enum class FileKind { kXtf, kCandump };

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// By extension (.xtf / .log), else by the first byte: 0x7B (XTF FileFormat) or '(' (candump).
FileKind file_kind(const std::string& path) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext == ".xtf") return FileKind::kXtf;
  if (ext == ".log") return FileKind::kCandump;
  io::check_input_file(path, "recording");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open '" + path + "'");
  char c = 0;
  while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {
  }
  if (static_cast<unsigned char>(c) == 0x7B) return FileKind::kXtf;
  if (c == '(') return FileKind::kCandump;
  throw UsageError("'" + path +
                   "' is neither an XTF file (.xtf, first byte 0x7B) nor a candump log (.log, "
                   "lines starting with '(')");
}

double ms(std::int64_t ns) {
  return static_cast<double>(ns) / 1e6;
}

void print_progress(const emulator::ReplaySummary& s) {
  std::fprintf(stderr, "replay: pass %llu, %llu packets sent, at %.1f of %.1f s of the recording\n",
               static_cast<unsigned long long>(s.pass + 1),
               static_cast<unsigned long long>(s.packets_sent),
               static_cast<double>(s.recording_position_ns) / kNsPerS,
               static_cast<double>(s.recording_span_ns) / kNsPerS);
}

void print_summary(const std::string& what, const emulator::ReplaySummary& s,
                   const emulator::ReplayRate& rate, bool xtf) {
  std::fprintf(stderr, "replay: %s%s\n", what.c_str(), s.stopped ? " (stopped)" : "");
  if (xtf) {
    std::fprintf(stderr, "  sent %llu packets (%llu pings) + %llu file headers, %llu bytes\n",
                 static_cast<unsigned long long>(s.packets_sent),
                 static_cast<unsigned long long>(s.pings_sent),
                 static_cast<unsigned long long>(s.file_headers_sent),
                 static_cast<unsigned long long>(s.bytes_sent));
  } else {
    std::fprintf(stderr, "  sent %llu frames (%llu data bytes)\n",
                 static_cast<unsigned long long>(s.packets_sent),
                 static_cast<unsigned long long>(s.bytes_sent));
  }
  std::fprintf(stderr,
               "  %llu pass(es) of %llu packets spanning %.3f s of recording, rate %s, "
               "%.3f s wall\n",
               static_cast<unsigned long long>(s.passes_completed),
               static_cast<unsigned long long>(s.packets_per_pass),
               static_cast<double>(s.recording_span_ns) / kNsPerS,
               emulator::to_string(rate).c_str(), static_cast<double>(s.wall_ns) / kNsPerS);
  if (s.paced_sends > 0) {
    std::fprintf(stderr, "  lateness: mean %.3f ms, max %.3f ms over %llu paced sends\n",
                 ms(s.total_late_ns) / static_cast<double>(s.paced_sends), ms(s.max_late_ns),
                 static_cast<unsigned long long>(s.paced_sends));
  }
  if (s.dropped || s.skipped || s.out_of_order) {
    std::fprintf(stderr, "  %llu dropped, %llu skipped, %llu out of order\n",
                 static_cast<unsigned long long>(s.dropped),
                 static_cast<unsigned long long>(s.skipped),
                 static_cast<unsigned long long>(s.out_of_order));
  }
}

int replay_xtf_file(const std::string& path, const Args& args,
                    const emulator::ReplayOptions& options, emulator::Clock& clock) {
  const auto udp = args.get("--udp");
  if (!udp) throw UsageError("an XTF recording replays to --udp HOST:PORT");
  if (args.has("--can")) throw UsageError("--can is for candump logs; XTF replays to --udp");
  net::HostPort dest;
  try {
    dest = net::parse_host_port(*udp);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--udp: ") + e.what());
  }
  if (dest.port == 0) throw UsageError("--udp " + *udp + ": port 0 is not a destination");
  net::UdpSender sender(dest);
  std::fprintf(stderr, "replay: %s -> %s at rate %s\n", path.c_str(), sender.describe().c_str(),
               emulator::to_string(options.rate).c_str());
  const auto summary = emulator::replay_xtf(
      path, [&](std::span<const std::uint8_t> d) { return sender.send(d); }, clock, options);
  print_summary(path + " -> " + sender.describe(), summary, options.rate, true);
  return 0;
}

int replay_candump_file(const std::string& path, const Args& args,
                        const emulator::ReplayOptions& options, emulator::Clock& clock) {
  if (args.has("--udp"))
    throw UsageError("--udp is for XTF recordings; a candump log replays to --can SPEC");
  if (args.has("--header-every")) throw UsageError("--header-every is for XTF recordings");
  const std::vector<std::string> specs = args.get_all("--can");
  if (specs.empty()) throw UsageError("a candump log replays to one or more --can SPEC");

  // the log's first channel name goes to the transports (a log:FILE copy keeps it); the reader
  // also reports a missing file before any transport is opened
  can::CanTransportOptions transport_options;
  {
    can::CandumpReader reader(path, true);
    if (const auto first = reader.next()) transport_options.channel = first->channel;
  }
  std::vector<std::unique_ptr<can::CanTransport>> owned;
  std::vector<can::CanTransport*> transports;
  std::vector<can::SocketcandServer*> servers;
  for (const std::string& spec : specs) {
    if (spec.starts_with("log:")) {
      std::error_code ec;
      if (std::filesystem::equivalent(spec.substr(4), path, ec))
        throw UsageError("--can " + spec + " would overwrite the log being replayed");
    }
    try {
      owned.push_back(can::open_can_transport(spec, transport_options));
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    transports.push_back(owned.back().get());
    if (auto* s = dynamic_cast<can::SocketcandServer*>(owned.back().get())) servers.push_back(s);
  }

  // socketcand servers: frames sent before a client is streaming are lost, so wait for one
  if (!servers.empty()) {
    const double wait_s = args.get_double("--wait-clients", 0.0, 1e9).value_or(-1.0);
    const std::int64_t t0 = clock.now_ns();
    for (can::SocketcandServer* s : servers) {
      if (wait_s == 0.0) break;
      std::fprintf(stderr, "replay: waiting for a client of the %s%s\n", s->describe().c_str(),
                   wait_s > 0.0 ? "" : " (Ctrl-C to stop)");
      while (s->streaming_clients() == 0 && !g_stop.load()) {
        const std::int64_t now = clock.now_ns();
        if (wait_s > 0.0 && static_cast<double>(now - t0) >= wait_s * kNsPerS) break;
        clock.sleep_until(now + 20'000'000);
      }
    }
  }
  std::string targets;
  for (const can::CanTransport* t : transports)
    targets += (targets.empty() ? "" : ", ") + t->describe();
  std::fprintf(stderr, "replay: %s -> %s at rate %s\n", path.c_str(), targets.c_str(),
               emulator::to_string(options.rate).c_str());
  const auto summary = emulator::replay_candump(path, transports, clock, options);
  if (!servers.empty() && !summary.stopped) {
    const std::int64_t until = clock.now_ns() + kSocketcandLingerNs;
    while (clock.now_ns() < until && !g_stop.load())
      clock.sleep_until(until);
  }
  print_summary(path + " -> " + targets, summary, options.rate, false);
  return 0;
}

int run_replay(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--udp"},
                         {"--can", true, true},
                         {"--rate"},
                         {"--loop"},
                         {"--header-every"},
                         {"--wait-clients"}});
  if (args.positionals().size() != 1) throw UsageError("expected one FILE.xtf or FILE.log");
  const std::string path = args.positionals()[0];

  emulator::ReplayOptions options;
  try {
    options.rate = emulator::parse_replay_rate(args.get_or("--rate", "original"));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  options.loops = static_cast<std::uint64_t>(args.get_int("--loop", 0, 1'000'000'000).value_or(1));
  if (const auto s = args.get_double("--header-every", 0.0, 3600.0))
    options.file_header_period_ns = static_cast<std::int64_t>(*s * kNsPerS);
  options.stop = &g_stop;
  options.on_progress = print_progress;
  g_stop = false;
  install_stop_handler();

  if (!std::filesystem::exists(path)) throw std::runtime_error("'" + path + "': no such file");
  emulator::MonotonicClock clock;
  return file_kind(path) == FileKind::kXtf ? replay_xtf_file(path, args, options, clock)
                                           : replay_candump_file(path, args, options, clock);
}

}  // namespace

const Command kReplayCommand{
    "replay", "replay an XTF recording over UDP or a candump log to CAN, with its timing",
    R"(usage: sonarloop replay FILE.xtf --udp HOST:PORT [options]
       sonarloop replay FILE.log --can SPEC [--can SPEC]... [options]

XTF: streams the recording as the live sonar stream does: the 1024-byte file header as one
datagram first (and again every --header-every seconds of recording time), then every packet of
the file as one datagram, byte for byte, paced by the pings' times (1/100 s resolution; equal
or backward times are repaired as described in emulator/replay.h; a ping more than 60 s after
the one before it, a corrupt date, or one with invalid date fields is not waited for: it follows
after the ping period, with a warning naming its byte offset). Non-sonar packets are sent as
recorded, right after the ping before them, so "file header + datagrams" is the file again.

candump log: sends every frame at its logged time relative to the first (absolute deadlines, as
can-utils' canplayer) to every --can transport, with its logged timestamp. Remote, error and
CAN FD frames are skipped and counted. With a socketcand server the replay starts once a client
is streaming (see --wait-clients) and keeps the server up 1 s after the last frame.

The whole file is checked before the first packet is sent: a truncated or corrupt XTF file is
reported with its byte offset, a malformed candump line with its line number; only a candump
log's last line without its newline (torn by a crash or a full disk) is ignored, with a
warning. Progress and a
summary (packets, bytes, duration, lateness) go to stderr. Ctrl-C stops after the current packet.

options:
  --udp HOST:PORT       XTF destination (e.g. 127.0.0.1:5600)
  --can SPEC            candump destination, repeatable: vcan0 (SocketCAN), socketcand:HOST:PORT
                        (a socketcand server clients such as python-can connect to), log:FILE
                        (candump log), none
  --rate R              original (default), max (no waiting) or a factor (2 = twice as fast)
  --loop N              play the file N times (default 1; 0 = until Ctrl-C)
  --header-every S      XTF: re-send the file header every S s of recording (default 1; 0 = only
                        at the start of each pass)
  --wait-clients S      socketcand: wait at most S s for a client before starting (default: until
                        one connects; 0 = do not wait)

examples:
  sonarloop replay tests/data/xtf/scotsman-iver2.xtf --udp 127.0.0.1:5600
  sonarloop replay out/run/pings.xtf --udp 127.0.0.1:5600 --rate 4 --loop 0
  sonarloop replay out/run/nav.log --can vcan0
  sonarloop replay nav.log --can socketcand:127.0.0.1:29536 --can log:copy.log --rate max
)",
    run_replay, 60};
SONARLOOP_REGISTER_COMMAND(kReplayCommand);

}  // namespace sonarloop::tools
