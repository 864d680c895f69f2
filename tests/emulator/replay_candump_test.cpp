// Replaying a candump log to CAN transports (emulator/replay.h): the same frames with their
// logged times, at their offsets / rate, a malformed line refused with its number, a torn last
// line ignored with a warning, and python-can reading the replay from our socketcand server.
#include "emulator/replay.h"

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "drivers/can/candump_log.h"
#include "drivers/can/socketcand_server.h"
#include "tests/emulator/simulated_clock.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;
using namespace sonarloop::emulator;
using sonarloop::testing::SimulatedClock;
using sonarloop::testing::TempDir;

namespace {

constexpr std::int64_t kLogClockStartNs = 1'000'000'000'000;

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

// A CAN transport that records what it is given, with the clock's time at each send.
class RecordingTransport final : public can::CanTransport {
 public:
  explicit RecordingTransport(Clock* clock = nullptr) : clock_(clock) {}
  void send(const can::CanFrame& frame, std::int64_t t_ns) override {
    frames.push_back({t_ns, frame});
    sent_at.push_back(clock_ ? clock_->now_ns() : 0);
  }
  std::string describe() const override { return "recording"; }
  void flush() override { ++flushes; }
  std::vector<can::TimedCanFrame> frames;
  std::vector<std::int64_t> sent_at;
  int flushes = 0;

 private:
  Clock* clock_;
};

// A small candump log: 40 frames at irregular intervals, plus one remote and one FD frame
// (not replayable) and one frame logged earlier than its predecessor.
struct TestLog {
  std::string text;
  std::vector<can::TimedCanFrame> data_frames;  // in file order
};

TestLog make_test_log() {
  TestLog log;
  std::int64_t t_us = 1'699'999'999'000'000;
  char line[128];
  for (int i = 0; i < 40; ++i) {
    t_us += 1000 + (i % 7) * 2500;  // 1..16 ms steps
    if (i == 25) t_us -= 15000;     // logged earlier than the frame before
    can::TimedCanFrame f;
    f.t_ns = t_us * 1000;
    f.frame.id = 0x09F80100u + static_cast<std::uint32_t>(i);
    f.frame.len = static_cast<std::uint8_t>(i % 9);
    std::string hex;
    for (int k = 0; k < f.frame.len; ++k) {
      f.frame.data[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(i * 11 + k);
      char b[4];
      std::snprintf(b, sizeof b, "%02X", f.frame.data[static_cast<std::size_t>(k)]);
      hex += b;
    }
    std::snprintf(line, sizeof line, "(%lld.%06lld) vcan0 %08X#%s\n",
                  static_cast<long long>(t_us / 1'000'000),
                  static_cast<long long>(t_us % 1'000'000), f.frame.id, hex.c_str());
    log.text += line;
    log.data_frames.push_back(f);
    // at the same time as the frame before them
    std::snprintf(line, sizeof line, "(%lld.%06lld) vcan0 ",
                  static_cast<long long>(t_us / 1'000'000),
                  static_cast<long long>(t_us % 1'000'000));
    if (i == 10) log.text += line + std::string("123#R\n");
    if (i == 20) log.text += line + std::string("18F11300##10102030405060708\n");
  }
  return log;
}

}  // namespace

TEST_CASE("replay candump: a log:FILE transport gets the same frames with their logged times") {
  TempDir dir("replay-candump-log");
  const TestLog log = make_test_log();
  write_text(dir.file("in.log"), log.text);
  auto out = can::open_can_transport("log:" + dir.file("out.log"));
  can::CanTransport* transports[] = {out.get()};
  MonotonicClock clock;
  ReplayOptions options;
  options.rate.max = true;
  std::vector<std::string> warnings;
  options.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  const ReplaySummary s = replay_candump(dir.file("in.log"), transports, clock, options);
  out.reset();  // closes the file
  CHECK(s.packets_per_pass == 42);
  CHECK(s.packets_sent == 40);
  CHECK(s.skipped == 2);       // the remote and the FD frame
  CHECK(s.out_of_order == 1);  // frame 25
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::Contains("in.log:12"));

  can::CandumpReader reader(dir.file("out.log"));
  std::size_t k = 0;
  while (const auto rec = reader.next()) {
    REQUIRE(k < log.data_frames.size());
    INFO("frame " << k);
    CHECK(rec->frame == log.data_frames[k].frame);
    CHECK(rec->t_ns == log.data_frames[k].t_ns);  // the logged time, not the replay's
    CHECK(rec->channel == "vcan0");
    ++k;
  }
  CHECK(k == log.data_frames.size());
}

TEST_CASE("replay candump: frames go out at their logged offsets / rate (simulated clock)") {
  TempDir dir("replay-candump-timing");
  const TestLog log = make_test_log();
  write_text(dir.file("in.log"), log.text);
  SimulatedClock clock(kLogClockStartNs);
  const std::int64_t start = clock.now_ns();
  RecordingTransport a(&clock), b(&clock);
  can::CanTransport* transports[] = {&a, &b};
  ReplayOptions options;
  options.rate.factor = 0.5;  // half speed
  options.loops = 2;
  options.on_warning = [](const std::string&) {};
  const ReplaySummary s = replay_candump(dir.file("in.log"), transports, clock, options);
  REQUIRE(a.frames.size() == 80);
  CHECK(b.frames.size() == 80);
  CHECK(a.flushes == 1);
  const std::int64_t t0 = log.data_frames.front().t_ns;
  std::int64_t span = 0;
  for (const auto& f : log.data_frames)
    span = std::max(span, f.t_ns - t0);
  CHECK(s.recording_span_ns == span);
  std::int64_t previous = 0;
  for (std::size_t i = 0; i < 80; ++i) {
    const auto& want = log.data_frames[i % 40];
    const std::int64_t pass_base = i < 40 ? 0 : span;
    // absolute deadlines; a frame logged before its predecessor goes out at once
    const std::int64_t deadline = (pass_base + (want.t_ns - t0)) * 2;
    const std::int64_t expected = std::max(deadline, previous);
    INFO("frame " << i);
    CHECK(a.frames[i].frame == want.frame);
    CHECK(a.frames[i].t_ns == want.t_ns);
    CHECK(a.sent_at[i] - start == expected);
    previous = a.sent_at[i] - start;
  }
  CHECK(s.passes_completed == 2);
}

TEST_CASE("replay candump: a malformed line is an error with its line number, nothing sent") {
  TempDir dir("replay-candump-bad");
  TestLog log = make_test_log();
  // line 7 becomes garbage
  std::string text;
  int line = 0;
  std::size_t pos = 0;
  while (pos < log.text.size()) {
    const std::size_t end = log.text.find('\n', pos);
    ++line;
    text += line == 7 ? std::string("(1699999999.1) vcan0 09F80107#0G")
                      : log.text.substr(pos, end - pos);
    text += '\n';
    pos = end + 1;
  }
  write_text(dir.file("bad.log"), text);
  SimulatedClock clock(kLogClockStartNs);
  RecordingTransport t(&clock);
  can::CanTransport* transports[] = {&t};
  CHECK_THROWS_WITH(replay_candump(dir.file("bad.log"), transports, clock),
                    Catch::Contains("bad.log:7:"));
  CHECK(t.frames.empty());
  CHECK_THROWS_WITH(replay_candump(dir.file("missing.log"), transports, clock),
                    Catch::Contains("missing.log") && Catch::Contains("cannot open"));
}

TEST_CASE("replay candump: a last line torn by a crash is ignored with a warning") {
  // issue 11: after SIGKILL nav.log ended mid-line and replay refused the whole log
  TempDir dir("replay-candump-torn");
  const TestLog log = make_test_log();
  const std::size_t lines =
      static_cast<std::size_t>(std::count(log.text.begin(), log.text.end(), '\n'));
  // torn inside the data: it would even parse, as a shorter frame
  write_text(dir.file("torn.log"), log.text + "(1700000000.000000) vcan0 09F80199#0102");
  SimulatedClock clock(kLogClockStartNs);
  RecordingTransport t(&clock);
  can::CanTransport* transports[] = {&t};
  std::vector<std::string> warnings;
  ReplayOptions options;
  options.rate.max = true;
  options.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  const ReplaySummary s = replay_candump(dir.file("torn.log"), transports, clock, options);
  CHECK(s.packets_sent == log.data_frames.size());
  REQUIRE(t.frames.size() == log.data_frames.size());
  CHECK(t.frames.back().frame == log.data_frames.back().frame);
  const std::string torn_at =
      "torn.log:" + std::to_string(lines + 1) + ": the last line has no newline";
  CHECK(std::count_if(warnings.begin(), warnings.end(), [&](const std::string& w) {
          return w.find(torn_at) != std::string::npos;
        }) == 1);
  // a malformed line that is not the last one is still an error
  write_text(dir.file("mid.log"), "(1700000000.000000) vcan0 09F8#0G\n" + log.text);
  CHECK_THROWS_WITH(replay_candump(dir.file("mid.log"), transports, clock),
                    Catch::Contains("mid.log:1:"));
}

TEST_CASE("replay candump: python-can reads the replay from our socketcand server") {
  TempDir dir("replay-candump-socketcand");
  const TestLog log = make_test_log();
  write_text(dir.file("in.log"), log.text);
  // python-can's socketcand interface (Debian python3-can 4.1) compares every frame with the log
  // (python-can's own CanutilsLogReader), timestamps included
  write_text(dir.file("peer.py"), R"(import logging, sys, time
import can
logging.getLogger("can.interfaces.socketcand.socketcand").setLevel(logging.ERROR)
port, log = int(sys.argv[1]), sys.argv[2]
want = [m for m in can.CanutilsLogReader(log) if not m.is_remote_frame and not m.is_fd]
bus = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="vcan0")
got = []
deadline = time.monotonic() + 60
while len(got) < len(want) and time.monotonic() < deadline:
    m = bus.recv(timeout=1.0)
    if m is not None:
        got.append(m)
bus.shutdown()
bad = 0
for i, (g, w) in enumerate(zip(got, want)):
    if g.arbitration_id != w.arbitration_id or bytes(g.data) != bytes(w.data) or \
            abs(g.timestamp - w.timestamp) > 1e-6:
        print(f"frame {i}: got {g.arbitration_id:08X} {bytes(g.data).hex()} {g.timestamp:.6f}, "
              f"want {w.arbitration_id:08X} {bytes(w.data).hex()} {w.timestamp:.6f}")
        bad += 1
print(f"python-can: {len(got)}/{len(want)} frames, {bad} mismatches", flush=True)
sys.exit(0 if len(got) == len(want) and bad == 0 else 1)
)");
  can::SocketcandServer server(net::HostPort{"127.0.0.1", 0});
  std::atomic<int> rc{-2};
  std::thread python([&] {
    rc = sonarloop::testing::run_command(std::string(SONARLOOP_PYTHON) + " " + dir.file("peer.py") +
                                         " " + std::to_string(server.bound_port()) + " " +
                                         dir.file("in.log"));
  });
  // wait (bounded) for python-can to stream
  for (int i = 0; i < 6000 && server.streaming_clients() == 0 && rc == -2; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  if (server.streaming_clients() == 0) {
    python.join();
    FAIL("python-can did not connect (exit code " << rc << ")");
  }
  can::CanTransport* transports[] = {&server};
  MonotonicClock clock;
  ReplayOptions options;  // original timing: ~0.3 s
  options.on_warning = [](const std::string&) {};
  const ReplaySummary s = replay_candump(dir.file("in.log"), transports, clock, options);
  python.join();
  CHECK(s.packets_sent == 40);
  CHECK(rc == 0);
  CHECK(server.stats().frames_sent == 40);
}
