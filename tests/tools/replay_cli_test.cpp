// End-to-end: the `sonarloop replay` command as a user runs it.
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "drivers/can/candump_log.h"
#include "drivers/can/socketcand_server.h"
#include "drivers/net/udp_receiver.h"
#include "drivers/net/udp_sender.h"
#include "drivers/xtf/xtf_file.h"
#include "tests/support/skip.h"
#include "tests/support/temp_dir.h"
#include "tests/tools/sonarloop_cli.h"

using sonarloop::testing::run_command;
using sonarloop::testing::TempDir;
namespace net = sonarloop::net;
namespace can = sonarloop::can;

namespace {

using sonarloop::testing::kBinary;
using sonarloop::testing::kRealXtf;

constexpr std::size_t kRealPings = 461;

using sonarloop::testing::slurp;

// Runs `sonarloop replay ARGS`, stderr to `err_file`; returns the exit status.
int replay(const std::string& args, const std::string& err_file) {
  return run_command(kBinary + " replay " + args + " > /dev/null 2> " + err_file);
}

// A candump log of 30 frames, 5..35 ms apart, on channel "can1".
std::string test_log() {
  std::string text;
  long long t_us = 1'700'000'000'000'000;
  char line[96];
  for (int i = 0; i < 30; ++i) {
    t_us += 5000 + (i % 4) * 10'000;
    std::snprintf(line, sizeof line, "(%lld.%06lld) can1 %08X#%02X%02X%02X\n", t_us / 1'000'000,
                  t_us % 1'000'000, 0x09F80100 + i, i, i * 3 & 0xFF, 0xA5);
    text += line;
  }
  return text;
}

}  // namespace

TEST_CASE("replay cli: the real XTF recording at --rate max arrives byte for byte over UDP") {
  TempDir dir("replay-cli-xtf");
  const sonarloop::xtf::XtfRawFile raw = sonarloop::xtf::read_raw_packets(kRealXtf);
  net::UdpReceiver rx(net::HostPort{"127.0.0.1", 0}, 8 << 20);
  std::atomic<int> rc{-2};
  std::thread cli([&] {
    rc = replay(kRealXtf + " --udp 127.0.0.1:" + std::to_string(rx.bound_port()) + " --rate max",
                dir.file("err.txt"));
  });
  std::vector<std::vector<std::uint8_t>> got;
  std::vector<std::uint8_t> buf(65536);
  std::size_t pings = 0;
  while (pings < kRealPings) {
    const auto d = rx.receive(buf, 10000);
    if (!d) break;  // 10 s of silence: the command has ended or hangs
    got.emplace_back(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(d->size));
    if (!(d->size == 1024 && buf[0] == 0x7B)) ++pings;
  }
  cli.join();
  CHECK(rc == 0);
  REQUIRE(!got.empty());
  CHECK(got.front() == raw.file_header);
  std::size_t k = 0;
  for (const auto& d : got) {
    if (d.size() == 1024 && d[0] == 0x7B) {
      CHECK(d == raw.file_header);
      continue;
    }
    REQUIRE(k < raw.packets.size());
    CHECK(d == raw.packets[k].bytes);
    ++k;
  }
  CHECK(k == kRealPings);
  const std::string err = slurp(dir.file("err.txt"));
  CHECK_THAT(err, Catch::Contains("sent 461 packets (461 pings)"));
  CHECK_THAT(err, Catch::Contains("spanning 52.230 s of recording, rate max"));
}

TEST_CASE("replay cli: a candump log to two log:FILE transports keeps frames, times, channel") {
  TempDir dir("replay-cli-candump");
  std::ofstream(dir.file("in.log")) << test_log();
  REQUIRE(replay(dir.file("in.log") + " --can log:" + dir.file("a.log") +
                     " --can log:" + dir.file("b.log") + " --rate 20",
                 dir.file("err.txt")) == 0);
  // the logged timestamps and the channel name are kept: the copies are the log again
  CHECK(slurp(dir.file("a.log")) == slurp(dir.file("in.log")));
  CHECK(slurp(dir.file("b.log")) == slurp(dir.file("in.log")));
  const std::string err = slurp(dir.file("err.txt"));
  CHECK_THAT(err, Catch::Contains("sent 30 frames (90 data bytes)"));
  CHECK_THAT(err, Catch::Contains("rate x20"));
  CHECK_THAT(err, Catch::Contains("lateness: mean"));
}

TEST_CASE("replay cli: python-can reads a candump replay from the socketcand server") {
  TempDir dir("replay-cli-socketcand");
  std::ofstream(dir.file("in.log")) << test_log();
  // a free port: bind an ephemeral one and release it
  std::uint16_t port = 0;
  {
    can::SocketcandServer probe(net::HostPort{"127.0.0.1", 0});
    port = probe.bound_port();
  }
  std::ofstream(dir.file("peer.py")) << R"(import logging, socket, sys, time
import can
logging.getLogger("can.interfaces.socketcand.socketcand").setLevel(logging.ERROR)
port, log = int(sys.argv[1]), sys.argv[2]
want = list(can.CanutilsLogReader(log))
deadline = time.monotonic() + 60
while True:  # the replay's server may not be listening yet
    try:
        socket.create_connection(("127.0.0.1", port), timeout=1).close()
        break
    except OSError:
        if time.monotonic() > deadline:
            sys.exit(2)
        time.sleep(0.05)
time.sleep(0.2)
bus = can.Bus(interface="socketcand", host="127.0.0.1", port=port, channel="can1")
got = []
while len(got) < len(want) and time.monotonic() < deadline:
    m = bus.recv(timeout=1.0)
    if m is not None:
        got.append(m)
bus.shutdown()
ok = len(got) == len(want) and all(
    g.arbitration_id == w.arbitration_id and bytes(g.data) == bytes(w.data) and
    abs(g.timestamp - w.timestamp) < 1e-6 for g, w in zip(got, want))
print(f"python-can: {len(got)}/{len(want)} frames, ok={ok}", flush=True)
sys.exit(0 if ok else 1)
)";
  std::atomic<int> py{-2};
  std::thread python([&] {
    py = run_command(std::string(SONARLOOP_PYTHON) + " " + dir.file("peer.py") + " " +
                     std::to_string(port) + " " + dir.file("in.log"));
  });
  const int rc = replay(dir.file("in.log") + " --can socketcand:127.0.0.1:" + std::to_string(port) +
                            " --wait-clients 60",
                        dir.file("err.txt"));
  python.join();
  CHECK(rc == 0);
  CHECK(py == 0);
  const std::string err = slurp(dir.file("err.txt"));
  CHECK_THAT(err, Catch::Contains("waiting for a client of the socketcand server"));
  CHECK_THAT(err, Catch::Contains("sent 30 frames"));
}

TEST_CASE("replay cli: bad input gives a clear error") {
  TempDir dir("replay-cli-bad");
  const std::string err = dir.file("err.txt");
  const std::string file = slurp(kRealXtf);

  // missing file
  CHECK(replay(dir.file("missing.xtf") + " --udp 127.0.0.1:5600", err) == 1);
  CHECK_THAT(slurp(err), Catch::Contains("missing.xtf': no such file"));

  // truncated XTF: cut inside the 3rd packet (offset 1024 + 2 x 4480)
  std::ofstream(dir.file("cut.xtf"), std::ios::binary) << file.substr(0, 1024 + 2 * 4480 + 10);
  CHECK(replay(dir.file("cut.xtf") + " --udp 127.0.0.1:5600 --rate max", err) == 1);
  CHECK_THAT(slurp(err), Catch::Contains("cut.xtf") && Catch::Contains("byte offset 9984"));

  // malformed candump line 3
  std::string log = test_log();
  const std::size_t l3 = log.find('\n', log.find('\n') + 1) + 1;
  log.insert(l3, "(1700000000.1) can1 09F80100#ZZ\n");
  std::ofstream(dir.file("bad.log")) << log;
  CHECK(replay(dir.file("bad.log") + " --can log:" + dir.file("out.log"), err) == 1);
  CHECK_THAT(slurp(err), Catch::Contains("bad.log:3:"));

  // a socketcand port in use
  can::SocketcandServer taken(net::HostPort{"127.0.0.1", 0});
  std::ofstream(dir.file("ok.log")) << test_log();
  CHECK(replay(dir.file("ok.log") +
                   " --can socketcand:127.0.0.1:" + std::to_string(taken.bound_port()),
               err) == 1);
  CHECK_THAT(slurp(err), Catch::Contains("Address already in use"));

  // usage errors (exit 2)
  CHECK(replay(kRealXtf, err) == 2);  // no --udp
  CHECK_THAT(slurp(err), Catch::Contains("--udp HOST:PORT"));
  CHECK(replay(kRealXtf + " --udp 127.0.0.1:0", err) == 2);
  CHECK(replay(kRealXtf + " --udp 127.0.0.1:5600 --rate fast", err) == 2);
  CHECK(replay(dir.file("ok.log") + " --udp 127.0.0.1:5600", err) == 2);
  CHECK(replay(dir.file("ok.log") + " --can log:" + dir.file("ok.log"), err) == 2);
  CHECK_THAT(slurp(err), Catch::Contains("overwrite"));
  CHECK(replay(dir.file("ok.log") + " --can bogus:spec", err) == 2);
}

TEST_CASE("replay cli: an unreachable UDP destination is a clear error", "[may_skip]") {
  // in a private network namespace (no routes, lo down) nothing can leave the machine
  if (run_command("unshare -n true > /dev/null 2>&1") != 0) {
    sonarloop::testing::skip_test(
        "'unshare -n' (a private network namespace) is not permitted here");
  }
  TempDir dir("replay-cli-unreachable");
  const std::string err = dir.file("err.txt");
  CHECK(run_command("unshare -n " + kBinary + " replay " + kRealXtf +
                    " --udp 10.1.2.3:5600 --rate max > /dev/null 2> " + err) == 1);
  CHECK_THAT(slurp(err),
             Catch::Contains("10.1.2.3:5600") && Catch::Contains("Network is unreachable"));
}
