#include "emulator/replay.h"

#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "drivers/can/candump_log.h"
#include "drivers/can/socketcand_server.h"
#include "drivers/net/udp_receiver.h"
#include "drivers/net/udp_sender.h"
#include "drivers/xtf/xtf_file.h"
#include "tests/emulator/simulated_clock.h"
#include "tests/emulator/time_units.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;
using namespace sonarloop::emulator;
using sonarloop::testing::kMs;
using sonarloop::testing::SimulatedClock;
using sonarloop::testing::TempDir;

namespace {

const std::string kRealXtf =
    std::string(SONARLOOP_SOURCE_DIR) + "/tests/data/xtf/scotsman-iver2.xtf";
constexpr std::size_t kRealPings = 461;

// Every send of a replay on the simulated clock happens exactly at its deadline, so the deadlines
// themselves can be checked (no wall clock involved). Started well away from 0.
constexpr std::int64_t kClockStartNs = 1'000'000'000'000;

std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

XtfPacketTime ping_at(std::optional<std::int64_t> t_ms, double spp_s = 0.0) {
  XtfPacketTime p;
  p.is_ping = true;
  if (t_ms) p.time_utc_ns = 1'700'000'000'000'000'000 + *t_ms * kMs;
  p.seconds_per_ping_s = spp_s;
  return p;
}

std::vector<std::int64_t> ms_of(const XtfSchedule& s) {
  std::vector<std::int64_t> out;
  for (std::int64_t t : s.t_ns)
    out.push_back(t / kMs);
  return out;
}

bool is_file_header_datagram(const std::vector<std::uint8_t>& d) {
  return d.size() == 1024 && d[0] == 0x7B;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// XTF schedule (pure)

TEST_CASE("xtf schedule: increasing ping times are kept as recorded") {
  const std::vector<XtfPacketTime> p = {ping_at(0), ping_at(100), ping_at(220), ping_at(330)};
  const XtfSchedule s = make_xtf_schedule(p);
  CHECK(ms_of(s) == std::vector<std::int64_t>{0, 100, 220, 330});
  CHECK(s.fallback_interval_ns == 110 * kMs);  // median of 100, 120, 110
  CHECK(s.span_ns == 330 * kMs);
  CHECK(s.pass_period_ns == 440 * kMs);
  CHECK(s.pings == 4);
  CHECK(s.spread_pings == 0);
  CHECK(s.fallback_pings == 0);
}

TEST_CASE("xtf schedule: pings sharing a 1/100 s time are spread evenly up to the next time") {
  // a 100 Hz-ish sonar logged at 10 ms resolution: three pings at 0, one at 30, two at 40, one at
  // 50
  const std::vector<XtfPacketTime> p = {ping_at(0),  ping_at(0),  ping_at(0), ping_at(30),
                                        ping_at(40), ping_at(40), ping_at(50)};
  const XtfSchedule s = make_xtf_schedule(p);
  CHECK(ms_of(s) == std::vector<std::int64_t>{0, 10, 20, 30, 40, 45, 50});
  CHECK(s.spread_pings == 3);
  CHECK(s.fallback_pings == 0);
  CHECK(s.span_ns == 50 * kMs);
}

TEST_CASE("xtf schedule: a run of equal times at the end steps by the median interval") {
  const std::vector<XtfPacketTime> p = {ping_at(0), ping_at(10), ping_at(20), ping_at(20),
                                        ping_at(20)};
  const XtfSchedule s = make_xtf_schedule(p);
  CHECK(s.fallback_interval_ns == 10 * kMs);
  CHECK(ms_of(s) == std::vector<std::int64_t>{0, 10, 20, 30, 40});
  CHECK(s.fallback_pings == 2);
}

TEST_CASE("xtf schedule: a backward or missing time continues after the fallback interval") {
  // the clock steps back 150 ms after ping 2; ping 5 has no valid time
  const std::vector<XtfPacketTime> p = {ping_at(0),  ping_at(100), ping_at(200),
                                        ping_at(50), ping_at(150), ping_at(std::nullopt),
                                        ping_at(250)};
  const XtfSchedule s = make_xtf_schedule(p);
  CHECK(s.fallback_interval_ns == 100 * kMs);
  // 3: 200 + 100 (fallback); 4: +100 as recorded; 5: +100 (fallback); 6: +100 (fallback: the
  // time before it is missing, so the recorded step is unknown)
  CHECK(ms_of(s) == std::vector<std::int64_t>{0, 100, 200, 300, 400, 500, 600});
  CHECK(s.fallback_pings == 3);
}

TEST_CASE("xtf schedule: a jump forward beyond kMaxPingGapNs is not waited for") {
  // ping 2's year is corrupt (about 197 years late); ping 4 has invalid date fields
  const std::int64_t years197_ms = 197LL * 365 * 24 * 3600 * 1000;
  const std::vector<XtfPacketTime> p = {ping_at(0),   ping_at(100),          ping_at(years197_ms),
                                        ping_at(300), ping_at(std::nullopt), ping_at(500)};
  const XtfSchedule s = make_xtf_schedule(p);
  CHECK(ms_of(s) == std::vector<std::int64_t>{0, 100, 200, 300, 400, 500});
  CHECK(s.time_jumps == 1);
  CHECK(s.first_time_jump == 2u);
  CHECK(s.invalid_times == 1);
  CHECK(s.first_invalid_time == 4u);
  // a step of exactly the bound is still waited for
  const std::int64_t gap_ms = kMaxPingGapNs / kMs;
  const XtfSchedule ok = make_xtf_schedule(std::vector<XtfPacketTime>{
      ping_at(0), ping_at(100), ping_at(100 + gap_ms), ping_at(200 + gap_ms)});
  CHECK(ok.t_ns.back() == 200 * kMs + kMaxPingGapNs);
  CHECK(ok.time_jumps == 0);
}

TEST_CASE("xtf schedule: SecondsPerPing is the fallback where set; without any time, 0.1 s") {
  const std::vector<XtfPacketTime> with_spp = {ping_at(0, 0.25), ping_at(0, 0.25),
                                               ping_at(0, 0.25)};
  CHECK(ms_of(make_xtf_schedule(with_spp)) == std::vector<std::int64_t>{0, 250, 500});
  const std::vector<XtfPacketTime> none = {ping_at(std::nullopt), ping_at(std::nullopt),
                                           ping_at(std::nullopt)};
  const XtfSchedule s = make_xtf_schedule(none);
  CHECK(s.fallback_interval_ns == kDefaultPingIntervalNs);
  CHECK(ms_of(s) == std::vector<std::int64_t>{0, 100, 200});
}

TEST_CASE("xtf schedule: other packets go with the ping before them (time 0 before the first)") {
  XtfPacketTime other;
  const std::vector<XtfPacketTime> p = {other, ping_at(500), other, other, ping_at(620), other};
  const XtfSchedule s = make_xtf_schedule(p);
  CHECK(ms_of(s) == std::vector<std::int64_t>{0, 0, 0, 0, 120, 120});
  CHECK(s.pings == 2);
  CHECK(make_xtf_schedule({}).t_ns.empty());
}

TEST_CASE("xtf schedule: the real recording's 461 ping times increase and are kept") {
  const XtfTimeline tl = read_xtf_timeline(kRealXtf);
  CHECK(tl.file_header.size() == 1024);
  REQUIRE(tl.packet_bytes.size() == kRealPings);
  CHECK(tl.schedule.pings == kRealPings);
  CHECK(tl.schedule.spread_pings == 0);
  CHECK(tl.schedule.fallback_pings == 0);
  CHECK(tl.schedule.span_ns == 52'230 * kMs);            // 21:13:08.00 .. 21:14:00.23
  CHECK(tl.schedule.fallback_interval_ns == 110 * kMs);  // steps of 0.10-0.14 s, median 0.11
}

// ---------------------------------------------------------------------------------------------
// XTF replay

TEST_CASE("replay xtf: the real recording at --rate max over UDP on 127.0.0.1 arrives intact") {
  const xtf::XtfRawFile raw = xtf::read_raw_packets(kRealXtf);
  REQUIRE(raw.packets.size() == kRealPings);
  // room for the whole stream in the socket buffer (granted up to 2 x net.core.rmem_max), and a
  // reader running alongside in case the kernel grants less
  net::UdpReceiver rx(net::HostPort{"127.0.0.1", 0}, 8 << 20);
  std::vector<std::vector<std::uint8_t>> got;
  std::atomic<bool> sender_done{false};
  std::thread reader([&] {
    std::vector<std::uint8_t> buf(net::kMaxUdpDatagramBytes + 1);
    std::size_t pings = 0;
    for (;;) {
      const auto d = rx.receive(buf, 2000);
      if (!d) {
        if (sender_done) return;  // 2 s of silence after the last send
        continue;
      }
      got.emplace_back(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(d->size));
      if (!is_file_header_datagram(got.back()) && ++pings == kRealPings) return;
    }
  });
  net::UdpSender tx(net::HostPort{"127.0.0.1", rx.bound_port()});
  MonotonicClock clock;
  ReplayOptions options;
  options.rate.max = true;
  const ReplaySummary s = replay_xtf(
      kRealXtf, [&](std::span<const std::uint8_t> d) { return tx.send(d); }, clock, options);
  sender_done = true;
  reader.join();

  CHECK(s.packets_sent == kRealPings);
  CHECK(s.pings_sent == kRealPings);
  CHECK(s.passes_completed == 1);
  CHECK(s.dropped == 0);
  CHECK(s.file_headers_sent >= 2);
  CHECK(s.bytes_sent == s.file_headers_sent * 1024 + (read_bytes(kRealXtf).size() - 1024));
  REQUIRE(!got.empty());
  CHECK(got.front() == raw.file_header);  // the file header datagram comes first
  std::vector<std::uint8_t> rebuilt = raw.file_header;
  std::size_t k = 0;
  std::size_t headers = 0;
  for (const auto& d : got) {
    if (is_file_header_datagram(d)) {
      CHECK(d == raw.file_header);
      ++headers;
      continue;
    }
    REQUIRE(k < raw.packets.size());
    INFO("ping datagram " << k);
    CHECK(d == raw.packets[k].bytes);  // in order, byte for byte
    rebuilt.insert(rebuilt.end(), d.begin(), d.end());
    ++k;
  }
  CHECK(k == kRealPings);
  CHECK(headers == s.file_headers_sent);
  // file header + the ping datagrams == the file
  CHECK(rebuilt == read_bytes(kRealXtf));
}

TEST_CASE("replay xtf: sends happen at the pings' recorded times / rate (simulated clock)") {
  const XtfTimeline tl = read_xtf_timeline(kRealXtf);
  const xtf::XtfFileContents contents = xtf::read_all_pings(kRealXtf);
  const std::int64_t t0 = *xtf::time_utc_ns(contents.pings.front().header);
  SimulatedClock clock(kClockStartNs);
  const std::int64_t start = clock.now_ns();
  std::vector<std::int64_t> ping_sent_at;
  std::vector<std::int64_t> header_sent_at;
  ReplayOptions options;
  options.rate.factor = 2.0;
  options.loops = 2;
  const ReplaySummary s = replay_xtf(
      kRealXtf,
      [&](std::span<const std::uint8_t> d) {
        (d.size() == 1024 && d[0] == 0x7B ? header_sent_at : ping_sent_at)
            .push_back(clock.now_ns() - start);
        return true;
      },
      clock, options);
  REQUIRE(ping_sent_at.size() == 2 * kRealPings);
  CHECK(s.passes_completed == 2);
  CHECK(s.max_late_ns == 0);
  CHECK(s.paced_sends == 2 * kRealPings);
  // pass 0: recorded time / 2; pass 1 starts one median interval (0.11 s) after the last ping
  for (std::size_t k = 0; k < kRealPings; ++k) {
    const std::int64_t rel = *xtf::time_utc_ns(contents.pings[k].header) - t0;
    INFO("ping " << k);
    CHECK(ping_sent_at[k] == rel / 2);
    CHECK(ping_sent_at[kRealPings + k] == (tl.schedule.pass_period_ns + rel) / 2);
  }
  CHECK(tl.schedule.pass_period_ns == (52'230 + 110) * kMs);
  CHECK(s.wall_ns == (2 * 52'230 + 110) * kMs / 2);
  // the file header: at each pass start and then after every >= 1 s of recording time
  REQUIRE(header_sent_at.size() == s.file_headers_sent);
  CHECK(header_sent_at.front() == 0);
  const std::int64_t pass1_start = tl.schedule.pass_period_ns / 2;
  int pass_starts = 0;
  for (std::size_t i = 1; i < header_sent_at.size(); ++i) {
    const std::int64_t gap_recording = 2 * (header_sent_at[i] - header_sent_at[i - 1]);
    INFO("header " << i);
    if (header_sent_at[i] == pass1_start) {
      ++pass_starts;  // always sent at a pass start
    } else {
      CHECK(gap_recording >= 1000 * kMs);
    }
    CHECK(gap_recording <= 1000 * kMs + 140 * kMs);  // within one ping step of the period
  }
  CHECK(pass_starts == 1);
}

TEST_CASE("replay xtf: a stop request ends the replay after the current packet") {
  SimulatedClock clock(kClockStartNs);
  std::atomic<bool> stop{false};
  int pings = 0;
  ReplayOptions options;
  options.stop = &stop;
  const ReplaySummary s = replay_xtf(
      kRealXtf,
      [&](std::span<const std::uint8_t> d) {
        if (d.size() != 1024 && ++pings == 10) stop = true;
        return true;
      },
      clock, options);
  CHECK(s.stopped);
  CHECK(s.packets_sent == 10);
  CHECK(pings == 10);
}

TEST_CASE("replay xtf: a ping with a corrupt year is paced by the ping period, with a warning") {
  // issue 11: `replay --rate 10` of such a file waited ~197 years after the last good packet
  TempDir dir("replay-corrupt-year");
  std::vector<std::uint8_t> bytes = read_bytes(kRealXtf);
  const XtfTimeline good = read_xtf_timeline(kRealXtf);
  std::uint64_t corrupt_offset = 0;
  std::size_t ping = 0;
  for (std::size_t i = 0; i < good.packet_offsets.size(); ++i) {
    if (bytes[good.packet_offsets[i] + 2] != xtf::kHeaderTypeSonar) continue;
    if (ping++ != 200) continue;
    corrupt_offset = good.packet_offsets[i];
    const std::uint64_t year_at = corrupt_offset + 14;  // WORD Year (docs/formats.md 1.5)
    const unsigned year = bytes[year_at] | (bytes[year_at + 1] << 8);
    const unsigned bad = year + 197;
    bytes[year_at] = static_cast<std::uint8_t>(bad & 0xFF);
    bytes[year_at + 1] = static_cast<std::uint8_t>(bad >> 8);
    break;
  }
  REQUIRE(corrupt_offset > 0);
  write_bytes(dir.file("corrupt.xtf"), bytes);
  SimulatedClock clock(kClockStartNs);
  std::vector<std::string> warnings;
  ReplayOptions options;
  options.rate.factor = 10.0;
  options.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  const ReplaySummary s = replay_xtf(
      dir.file("corrupt.xtf"), [](std::span<const std::uint8_t>) { return true; }, clock, options);
  CHECK(s.pings_sent == kRealPings);
  // as long as the good file, give or take the ping steps around the corrupt one
  CHECK(s.wall_ns <= (52'230 + 1'000) * kMs / 10);
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::Contains("byte offset " + std::to_string(corrupt_offset)) &&
                              Catch::Contains("more than 60 s after the ping before it") &&
                              Catch::Contains("paced by the ping period"));
}

TEST_CASE("replay xtf: packets too large for a datagram are skipped and reported") {
  SimulatedClock clock(kClockStartNs);
  std::vector<std::string> warnings;
  ReplayOptions options;
  options.rate.max = true;
  options.max_datagram_bytes = 4000;  // the real pings have 4480 bytes
  options.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  int sent = 0;
  const ReplaySummary s = replay_xtf(
      kRealXtf, [&](std::span<const std::uint8_t>) { return ++sent > 0; }, clock, options);
  CHECK(s.skipped == kRealPings);
  CHECK(s.packets_sent == 0);
  CHECK(static_cast<std::uint64_t>(sent) == s.file_headers_sent);
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::Contains("byte offset 1024") && Catch::Contains("4480 bytes"));
}

TEST_CASE("replay xtf: refused datagrams (nobody listening) are counted, not fatal") {
  // bind a port, learn its number, close it: sends to it are refused
  std::uint16_t port = 0;
  {
    net::UdpReceiver probe(net::HostPort{"127.0.0.1", 0});
    port = probe.bound_port();
  }
  net::UdpSender tx(net::HostPort{"127.0.0.1", port});
  SimulatedClock clock(kClockStartNs);
  std::vector<std::string> warnings;
  ReplayOptions options;
  options.rate.max = true;
  options.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  const ReplaySummary s = replay_xtf(
      kRealXtf, [&](std::span<const std::uint8_t> d) { return tx.send(d); }, clock, options);
  CHECK(s.packets_sent == kRealPings);
  CHECK(s.dropped > 0);
  CHECK(warnings.size() == 1);
}

TEST_CASE("replay xtf: truncated, corrupt and missing files are errors before anything is sent") {
  TempDir dir("replay-xtf-bad");
  const std::vector<std::uint8_t> file = read_bytes(kRealXtf);
  int sent = 0;
  const DatagramSink count = [&](std::span<const std::uint8_t>) { return ++sent > 0; };
  SimulatedClock clock(kClockStartNs);

  // cut inside the 11th packet
  const std::uint64_t packet10 = 1024 + 10 * 4480;
  write_bytes(dir.file("truncated.xtf"),
              std::vector<std::uint8_t>(file.begin(), file.begin() + packet10 + 100));
  try {
    replay_xtf(dir.file("truncated.xtf"), count, clock);
    FAIL("no error for a truncated file");
  } catch (const xtf::XtfFormatError& e) {
    CHECK(e.offset() == packet10);
    CHECK_THAT(e.what(), Catch::Contains("truncated.xtf") &&
                             Catch::Contains("byte offset " + std::to_string(packet10)) &&
                             Catch::Contains("runs past the end of the file"));
  }

  // bad magic in the 6th packet
  std::vector<std::uint8_t> corrupt = file;
  const std::uint64_t packet5 = 1024 + 5 * 4480;
  corrupt[packet5] = 0x12;
  write_bytes(dir.file("corrupt.xtf"), corrupt);
  try {
    replay_xtf(dir.file("corrupt.xtf"), count, clock);
    FAIL("no error for a corrupt file");
  } catch (const xtf::XtfFormatError& e) {
    CHECK(e.offset() == packet5);
    CHECK_THAT(e.what(), Catch::Contains("bad magic"));
  }

  // a file header cut short
  write_bytes(dir.file("short.xtf"), std::vector<std::uint8_t>(file.begin(), file.begin() + 700));
  CHECK_THROWS_AS(replay_xtf(dir.file("short.xtf"), count, clock), xtf::XtfFormatError);

  CHECK_THROWS_WITH(replay_xtf(dir.file("missing.xtf"), count, clock),
                    Catch::Contains("missing.xtf"));
  CHECK(sent == 0);
}

TEST_CASE("replay rate: parsing") {
  CHECK_FALSE(parse_replay_rate("original").max);
  CHECK(parse_replay_rate("original").factor == 1.0);
  CHECK(parse_replay_rate("max").max);
  CHECK(parse_replay_rate("2.5").factor == 2.5);
  CHECK(to_string(parse_replay_rate("0.5")) == "x0.5");
  CHECK_THROWS_WITH(parse_replay_rate("0"), Catch::Contains("expected original, max"));
  CHECK_THROWS_AS(parse_replay_rate("fast"), std::invalid_argument);
  CHECK_THROWS_AS(parse_replay_rate("-1"), std::invalid_argument);
  CHECK_THROWS_AS(parse_replay_rate("nan"), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// candump replay

TEST_CASE("replay xtf: a record claiming 2.1 GB is skipped by seeking, never read into memory") {
  // the real file's header and first ping, a packet whose NumBytesThisRecord is 2.1e9 (a sparse
  // file: the disk holds almost nothing of it), then the second ping again
  TempDir dir("replay-oversize");
  const std::vector<std::uint8_t> real = read_bytes(kRealXtf);
  constexpr std::size_t kPing = 4480;  // the real pings' packet size
  std::vector<std::uint8_t> head(real.begin(), real.begin() + 1024 + kPing);
  const std::uint32_t huge = 2'100'000'000u;
  const std::uint8_t start[14] = {0xCE,
                                  0xFA,
                                  0,
                                  0,
                                  2,
                                  0,
                                  0,
                                  0,
                                  0,
                                  0,
                                  static_cast<std::uint8_t>(huge),
                                  static_cast<std::uint8_t>(huge >> 8),
                                  static_cast<std::uint8_t>(huge >> 16),
                                  static_cast<std::uint8_t>(huge >> 24)};
  head.insert(head.end(), start, start + 14);
  const std::string path = dir.file("huge.xtf");
  write_bytes(path, head);
  std::filesystem::resize_file(path, 1024 + kPing + huge);
  {
    std::ofstream out(path, std::ios::binary | std::ios::app);
    out.write(reinterpret_cast<const char*>(real.data() + 1024 + kPing), kPing);
  }
  rusage before{};
  getrusage(RUSAGE_SELF, &before);
  SimulatedClock clock(kClockStartNs);
  std::vector<std::string> warnings;
  ReplayOptions options;
  options.rate.max = true;
  options.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  std::vector<std::size_t> sent;
  const ReplaySummary s = replay_xtf(
      path,
      [&](std::span<const std::uint8_t> d) {
        sent.push_back(d.size());
        return true;
      },
      clock, options);
  rusage after{};
  getrusage(RUSAGE_SELF, &after);
  CHECK(s.skipped == 1);
  CHECK(s.pings_sent == 2);
  CHECK(sent == std::vector<std::size_t>{1024, kPing, kPing});
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::Contains("2100000000 bytes") && Catch::Contains("skipped"));
  // the peak resident memory grew by far less than the record (kB)
  CHECK(after.ru_maxrss - before.ru_maxrss < 200'000);
  // the readers that do read packets whole refuse it with the reason, without reading it
  xtf::XtfReader reader(path);
  xtf::XtfRecord record;
  REQUIRE(reader.next(record));
  CHECK_THROWS_WITH(reader.next(record), Catch::Contains("more than the 64 MB a packet may be"));
}
