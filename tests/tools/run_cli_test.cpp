// End-to-end: `sonarloop run` as a user runs it, on 127.0.0.1 only. A test receiver takes every
// UDP datagram; python-can (Debian python3-can, /usr/bin/python3) reads nav.log and receives the
// navigation live from the socketcand server; SocketCAN where the kernel has it.
#include <arpa/inet.h>
#include <net/if.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "common/geodesy.h"
#include "config/loader/scenario_loader.h"
#include "drivers/can/candump_log.h"
#include "drivers/can/socketcan.h"
#include "drivers/imc/imc_codec.h"
#include "drivers/n2k/messages.h"
#include "drivers/net/udp_receiver.h"
#include "drivers/xtf/xtf_codec.h"
#include "drivers/xtf/xtf_file.h"
#include "emulator/emulator.h"
#include "sim/vehicle/nav_sensor.h"
#include "sim/vehicle/trajectory.h"
#include "tests/emulator/test_scenario.h"
#include "tests/support/skip.h"
#include "tests/support/temp_dir.h"
#include "tests/tools/sonarloop_cli.h"

using namespace sonarloop;

namespace {

using sonarloop::testing::kBinary;
using sonarloop::testing::kPython;

const std::string kHelpers = std::string(SONARLOOP_SOURCE_DIR) + "/tests/emulator/";

using sonarloop::testing::slurp;

void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Runs the binary; stderr goes to `err_file` (or /dev/null). Returns the exit status.
int run(const std::string& args, const std::string& err_file = "/dev/null") {
  return testing::run_command(kBinary + " " + args + " > /dev/null 2> " + err_file);
}

// Receives datagrams on a loopback port in a thread until stopped.
class Receiver {
 public:
  Receiver() : rx_(net::parse_host_port("127.0.0.1:0"), 8 << 20) {
    // as root, raise the buffer beyond net.core.rmem_max so a descheduled test thread loses
    // nothing while the emulator runs at --rate max (best effort)
    const int bytes = 32 << 20;
    setsockopt(rx_.fd(), SOL_SOCKET, SO_RCVBUFFORCE, &bytes, sizeof bytes);
    thread_ = std::thread([this] {
      std::vector<std::uint8_t> buf(70000);
      while (!stop_) {
        const auto d = rx_.receive(buf, 50);
        if (!d) continue;
        std::lock_guard<std::mutex> lock(mu_);
        got_.emplace_back(buf.begin(), buf.begin() + static_cast<long>(d->size));
        truncated_ += d->truncated ? 1 : 0;
      }
    });
  }
  ~Receiver() { finish(); }
  // Stops after the stream has been quiet for a moment.
  const std::vector<std::vector<std::uint8_t>>& finish() {
    if (thread_.joinable()) {
      std::size_t n = SIZE_MAX;
      while (n != got_size()) {
        n = got_size();
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
      }
      stop_ = true;
      thread_.join();
    }
    return got_;
  }
  std::uint16_t port() const { return rx_.bound_port(); }
  int truncated() const { return truncated_; }

 private:
  std::size_t got_size() {
    std::lock_guard<std::mutex> lock(mu_);
    return got_.size();
  }
  net::UdpReceiver rx_;
  std::atomic<bool> stop_{false};
  std::mutex mu_;
  std::vector<std::vector<std::uint8_t>> got_;
  int truncated_ = 0;
  std::thread thread_;
};

// Starts the binary in the background (stderr to err_file); returns its pid.
pid_t spawn(const std::vector<std::string>& args, const std::string& err_file) {
  const pid_t pid = fork();
  if (pid == 0) {
    FILE* f = std::freopen(err_file.c_str(), "w", stderr);
    (void)f;
    FILE* o = std::freopen("/dev/null", "w", stdout);
    (void)o;
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(kBinary.c_str()));
    for (const auto& a : args)
      argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(kBinary.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool wait_for_text(const std::string& file, const std::string& text, int seconds) {
  for (int i = 0; i < seconds * 20; ++i) {
    if (slurp(file).find(text) != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

std::size_t count_lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace

TEST_CASE("run cli: at --rate max every datagram arrives, valid, in order, equal to pings.xtf") {
  testing::TempDir dir("run-cli-udp");
  write_file(dir.file("s.yaml"), testing::small_scenario_yaml());
  Receiver rx;
  REQUIRE(run("run " + dir.file("s.yaml") +
                  " --rate max --duration 10 --udp 127.0.0.1:" + std::to_string(rx.port()) +
                  " --record " + dir.file("a") + " --stats-json " + dir.file("a.json"),
              dir.file("a.err")) == 0);
  const auto& got = rx.finish();
  CHECK(rx.truncated() == 0);
  INFO(slurp(dir.file("a.err")));

  const std::string recorded = slurp(dir.file("a/pings.xtf"));
  REQUIRE(recorded.size() > 1024);
  const xtf::XtfFileHeader header = xtf::decode_file_header(
      std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(recorded.data()), 1024));
  // the stream: the file header first, again every 2 s of pings; each ping one XTF packet
  REQUIRE(!got.empty());
  REQUIRE(xtf::classify_datagram(got.front()) == xtf::DatagramKind::kFileHeader);
  std::string stream(recorded.begin(), recorded.begin() + 1024);
  CHECK(std::string(got.front().begin(), got.front().end()) == stream);
  std::size_t headers = 0, pings = 0;
  for (const auto& d : got) {
    const auto kind = xtf::classify_datagram(d);
    REQUIRE(kind != xtf::DatagramKind::kInvalid);
    CHECK(d.size() <= net::kMaxUdpDatagramBytes);
    if (kind == xtf::DatagramKind::kFileHeader) {
      ++headers;
      CHECK(std::string(d.begin(), d.end()) == recorded.substr(0, 1024));
      continue;
    }
    const xtf::XtfPing ping = xtf::decode_ping(d, header);  // throws if malformed
    REQUIRE(ping.header.ping_number == pings);              // consecutive, none lost
    REQUIRE(ping.channels.size() == 2);
    ++pings;
    stream.append(d.begin(), d.end());
  }
  // 10 s of pings at 26.9 ms: 372; a header at t = 0, 2, 4, 6, 8 s
  CHECK(pings > 300);
  CHECK(headers == 5);
  // "file header + ping datagrams" is the recording, byte for byte, and a valid XTF file
  CHECK(stream == recorded);
  write_file(dir.file("stream.xtf"), stream);
  const auto file = xtf::read_all_pings(dir.file("stream.xtf"));
  CHECK(file.pings.size() == pings);
  CHECK(file.stats.other_packets == 0);
  // truth.csv: a row per ping
  CHECK(count_lines(slurp(dir.file("a/truth.csv"))) == pings + 1);
  const std::string stats = slurp(dir.file("a.json"));
  CHECK(stats.find("\"sent\": " + std::to_string(pings)) != std::string::npos);
  CHECK(stats.find("\"header_datagrams\": 5") != std::string::npos);

  // the same scenario and seed, one render thread, no stream: the same files byte for byte
  REQUIRE(run("run " + dir.file("s.yaml") +
              " --rate max --duration 10 --threads 1 --quiet "
              "--record " +
              dir.file("b")) == 0);
  CHECK(slurp(dir.file("b/pings.xtf")) == recorded);
  CHECK(slurp(dir.file("b/nav.log")) == slurp(dir.file("a/nav.log")));
  CHECK(slurp(dir.file("b/truth.csv")) == slurp(dir.file("a/truth.csv")));
}

TEST_CASE("run cli: --imc sends IMC packets that decode, counted in --stats-json") {
  testing::TempDir dir("run-cli-imc");
  write_file(dir.file("s.yaml"), testing::small_scenario_yaml());
  Receiver rx;
  REQUIRE(run("run " + dir.file("s.yaml") +
                  " --rate max --duration 3 --imc udp:127.0.0.1:" + std::to_string(rx.port()) +
                  " --imc-system 0x2101 --imc-name emu --stats-json " + dir.file("a.json"),
              dir.file("a.err")) == 0);
  const auto& got = rx.finish();
  INFO(slurp(dir.file("a.err")));
  REQUIRE(!got.empty());
  std::size_t sonar = 0, state = 0, announce = 0;
  for (const auto& d : got) {
    imc::Packet p;
    REQUIRE(imc::decode(d, p) == imc::DecodeStatus::kOk);
    CHECK(p.header.src == 0x2101);
    sonar += std::holds_alternative<imc::SonarData>(p.message);
    state += std::holds_alternative<imc::EstimatedState>(p.message);
    if (const auto* a = std::get_if<imc::Announce>(&p.message)) {
      CHECK(a->sys_name == "emu");
      ++announce;
    }
  }
  const std::string json = slurp(dir.file("a.json"));
  const std::size_t imc = json.find("\"imc\": {");
  REQUIRE(imc != std::string::npos);
  CHECK(json.find("\"datagrams\": " + std::to_string(got.size()) + ",", imc) ==
        json.find("\"datagrams\": ", imc));
  CHECK(json.find("\"sent\": " + std::to_string(sonar) + ",") != std::string::npos);
  CHECK(state >= 29);  // 10 Hz for 3 s
  CHECK(announce == 1);
}

TEST_CASE("run cli: python-can reads nav.log; positions and headings match the vehicle's nav") {
  testing::TempDir dir("run-cli-candump");
  write_file(dir.file("s.yaml"), testing::small_scenario_yaml());
  REQUIRE(run("run " + dir.file("s.yaml") + " --rate max --duration 5 --quiet --record " +
              dir.file("r")) == 0);
  REQUIRE(testing::run_command(kPython + " " + kHelpers + "python_candump_frames.py " +
                               dir.file("r/nav.log") + " > " + dir.file("frames.txt")) == 0);
  const config::Scenario sc = config::load_scenario(dir.file("s.yaml"));
  const vehicle::Trajectory traj(sc.vehicle.trajectory);
  const vehicle::NavSensorModel nav(sc.vehicle.nav, sc.scene.seed);
  const LocalTangentPlane ltp(
      GeoPoint{sc.scene.origin.latitude_deg, sc.scene.origin.longitude_deg});
  std::istringstream lines(slurp(dir.file("frames.txt")));
  std::string line;
  int frames = 0, positions = 0, headings = 0, attitudes = 0;
  while (std::getline(lines, line)) {
    long long us = 0;
    unsigned id = 0;
    char data[32] = {};
    REQUIRE(std::sscanf(line.c_str(), "%lld %x %31s", &us, &id, data) == 3);
    can::CanFrame f;
    f.id = id;
    f.extended = true;
    f.len = 8;
    REQUIRE(std::string(data).size() == 16);
    for (int i = 0; i < 8; ++i)
      f.data[static_cast<std::size_t>(i)] =
          static_cast<std::uint8_t>(std::stoi(std::string(data + 2 * i, 2), nullptr, 16));
    ++frames;
    const SimTime t = us * 1000 - emulator::kMaxRateEpochUtcNs;
    const vehicle::NavSolution want = nav.measure(traj.state_at(t));
    if (const auto p = n2k::decode<n2k::PositionRapidUpdate>(f)) {
      const GeoPoint g = ltp.to_geodetic(want.north_m, want.east_m);
      CHECK(*p->latitude_deg == Approx(g.latitude_deg).margin(0.51e-7));  // 1e-7 deg steps
      CHECK(*p->longitude_deg == Approx(g.longitude_deg).margin(0.51e-7));
      ++positions;
    } else if (const auto h = n2k::decode<n2k::VesselHeading>(f)) {
      CHECK(*h->heading_rad == Approx(want.heading).margin(0.51e-4));  // 1e-4 rad steps
      ++headings;
    } else if (const auto a = n2k::decode<n2k::Attitude>(f)) {
      CHECK(*a->pitch_rad == Approx(want.pitch).margin(0.51e-4));
      CHECK(*a->roll_rad == Approx(want.roll).margin(0.51e-4));
      ++attitudes;
    }
  }
  // python-can read every line of the log
  std::size_t logged = 0;
  can::CandumpReader reader(dir.file("r/nav.log"));
  while (reader.next())
    ++logged;
  CHECK(static_cast<std::size_t>(frames) == logged);
  CHECK(positions == 50);  // 5 s at 10 Hz
  CHECK(headings == 50);
  CHECK(attitudes == 5);
}

TEST_CASE("run cli: python-can receives the navigation live from the socketcand server") {
  testing::TempDir dir("run-cli-socketcand");
  write_file(dir.file("s.yaml"), testing::small_scenario_yaml());
  const int rc = testing::run_command(kPython + " " + kHelpers + "python_socketcand_live.py " +
                                      kBinary + " " + dir.file("s.yaml") + " " + dir.file("r") +
                                      " 4 30 > " + dir.file("py.txt") + " 2>&1");
  INFO(slurp(dir.file("py.txt")));
  CHECK(rc == 0);
}

TEST_CASE("run cli: SocketCAN where the kernel has it", "[may_skip]") {
  std::string reason;
  if (!can::SocketCanTransport::kernel_supports_can(&reason)) {
    // then `--can vcan0` is a clear error that names the fallbacks (REQUIRE: a failure here
    // must fail the test, not end in the skip)
    testing::TempDir dir("run-cli-nocan");
    write_file(dir.file("s.yaml"), testing::small_scenario_yaml());
    REQUIRE(run("run " + dir.file("s.yaml") + " --can vcan0 --duration 1", dir.file("err")) == 1);
    const std::string err = slurp(dir.file("err"));
    INFO(err);
    REQUIRE(err.find("vcan0") != std::string::npos);
    REQUIRE(err.find("socketcand") != std::string::npos);
    testing::skip_test("socket(AF_CAN) does not work here (" + reason + ")");
  }
  if (if_nametoindex("vcan0") == 0) {
    testing::skip_test(
        "socket(AF_CAN) works but there is no vcan0 interface (modprobe vcan; ip link add dev "
        "vcan0 type vcan; ip link set up vcan0)");
  }
  testing::TempDir dir("run-cli-socketcan");
  write_file(dir.file("s.yaml"), testing::small_scenario_yaml());
  const pid_t pid =
      spawn({"run", dir.file("s.yaml"), "--can", "vcan0", "--duration", "4", "--stats-every", "0"},
            dir.file("err"));
  REQUIRE(wait_for_text(dir.file("err"), "running", 60));
  const int rc =
      testing::run_command(kPython + " " + kHelpers + "python_socketcan_live.py vcan0 2 20 > " +
                           dir.file("py") + " 2>&1");
  INFO(slurp(dir.file("py")));
  CHECK(rc == 0);
  CHECK(wait_exit(pid) == 0);
}

TEST_CASE("run cli: SIGINT stops cleanly and leaves valid recordings") {
  testing::TempDir dir("run-cli-sigint");
  write_file(dir.file("s.yaml"), testing::small_scenario_yaml());
  const pid_t pid = spawn({"run", dir.file("s.yaml"), "--duration", "60", "--record", dir.file("r"),
                           "--stats-every", "0", "--stats-json", dir.file("s.json")},
                          dir.file("err"));
  REQUIRE(wait_for_text(dir.file("err"), "running", 60));
  // let it publish for a while (no assertion on how long it took)
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  kill(pid, SIGINT);
  CHECK(wait_exit(pid) == 0);
  const std::string err = slurp(dir.file("err"));
  INFO(err);
  CHECK(err.find("stopped by SIGINT") != std::string::npos);
  // whole packets only, one truth row per ping, a log python-can reads
  const auto file = xtf::read_all_pings(dir.file("r/pings.xtf"));
  CHECK(file.pings.size() > 0);
  CHECK(count_lines(slurp(dir.file("r/truth.csv"))) == file.pings.size() + 1);
  CHECK(testing::run_command(kPython + " " + kHelpers + "python_candump_frames.py " +
                             dir.file("r/nav.log") + " > /dev/null 2>&1") == 0);
  CHECK(slurp(dir.file("s.json")).find("\"sent\": " + std::to_string(file.pings.size())) !=
        std::string::npos);
}

TEST_CASE("run cli: a long start-up shows progress and SIGTERM stops it cleanly") {
  // issue 11: very long trajectories spent minutes in start-up, silent, ignoring Ctrl-C. Here a
  // 1000 km line sampled every 5 cm: 20 million seabed points to plan the depth on
  testing::TempDir dir("run-cli-long-startup");
  std::string y = testing::small_scenario_yaml();
  y.replace(y.find("length_m: 50.0"), 14, "length_m: 1000000.0");
  y.replace(y.find("depth: {mode: depth, depth_m: 14.0}"), 35,
            "depth: {mode: depth, depth_m: 14.0, profile_step_m: 0.05}");
  write_file(dir.file("long.yaml"), y);
  const pid_t pid =
      spawn({"run", dir.file("long.yaml"), "--record", dir.file("r")}, dir.file("err"));
  const bool progress = wait_for_text(dir.file("err"), "preparing: sampling the seabed", 120);
  kill(pid, SIGTERM);
  const int rc = wait_exit(pid);
  const std::string err = slurp(dir.file("err"));
  INFO(err);
  CHECK(progress);
  CHECK(rc == 0);
  CHECK(err.find("of 20000001 points; Ctrl-C stops)") != std::string::npos);
  CHECK(err.find("sonarloop run: stopped during start-up (nothing sent) by SIGTERM") !=
        std::string::npos);
}

TEST_CASE("run cli: after SIGKILL every recorded line is whole and replay reads nav.log") {
  // issue 11: buffered writes left nav.log and truth.csv torn mid-line (or empty)
  testing::TempDir dir("run-cli-sigkill");
  write_file(dir.file("s.yaml"), testing::small_scenario_yaml());
  const pid_t pid = spawn({"run", dir.file("s.yaml"), "--duration", "60", "--record", dir.file("r"),
                           "--stats-every", "0"},
                          dir.file("err"));
  REQUIRE(wait_for_text(dir.file("err"), "running", 60));
  std::this_thread::sleep_for(std::chrono::milliseconds(2000));
  kill(pid, SIGKILL);
  wait_exit(pid);
  const std::string nav = slurp(dir.file("r/nav.log"));
  const std::string truth = slurp(dir.file("r/truth.csv"));
  REQUIRE(!nav.empty());
  CHECK(nav.back() == '\n');
  REQUIRE(!truth.empty());
  CHECK(truth.back() == '\n');
  // the packet and its truth row are two writes: SIGKILL may fall between them
  const auto file = xtf::read_all_pings(dir.file("r/pings.xtf"));
  CHECK(file.pings.size() > 0);
  const std::size_t rows = count_lines(truth) - 1;
  CHECK((rows == file.pings.size() || rows + 1 == file.pings.size()));
  CHECK(
      run("replay " + dir.file("r/nav.log") + " --can log:" + dir.file("copy.log") + " --rate max",
          dir.file("replay.err")) == 0);
  CHECK(slurp(dir.file("copy.log")).size() == nav.size());
}

TEST_CASE("run cli: a full disk under --record: the run goes on and says so, with statistics") {
  // /dev/full fails every write with ENOSPC: nav.log on a full disk
  testing::TempDir dir("run-cli-full-disk");
  write_file(dir.file("s.yaml"), testing::small_scenario_yaml());
  std::filesystem::create_directories(dir.file("r"));
  std::filesystem::create_symlink("/dev/full", dir.file("r/nav.log"));
  const int rc = run("run " + dir.file("s.yaml") + " --duration 2 --rate max --record " +
                         dir.file("r") + " --stats-json " + dir.file("s.json"),
                     dir.file("err"));
  const std::string err = slurp(dir.file("err"));
  INFO(err);
  CHECK(rc == 1);
  const std::string nav_log = dir.file("r/nav.log");
  CHECK(err.find("warning: --record stopped: candump log " + nav_log) != std::string::npos);
  CHECK(err.find("No space left on device (ENOSPC: the disk is full)") != std::string::npos);
  // the final statistics, then the error
  const auto stats_at = err.find("sonarloop run: done after ");
  const auto error_at = err.find("sonarloop run: error: --record: candump log " + nav_log);
  CHECK(stats_at != std::string::npos);
  CHECK(error_at != std::string::npos);
  CHECK(stats_at < error_at);
  CHECK(slurp(dir.file("s.json")).find("\"sent\"") != std::string::npos);
  // the other recordings stop there too, whole
  CHECK_NOTHROW(xtf::read_all_pings(dir.file("r/pings.xtf")));
  CHECK(slurp(dir.file("r/truth.csv")).back() == '\n');
}

TEST_CASE("run cli: --memory-budget bounds the seabed's caches; evicted tiles, the same pings") {
  // the default scenario (2.5 cm heightmap, 50 m range): 10 s need more tiles than 16 MB hold
  testing::TempDir dir("run-cli-budget");
  const std::string common = "run --rate max --duration 10 --threads 2 --quiet --record ";
  REQUIRE(run(common + dir.file("a") + " --stats-json " + dir.file("a.json")) == 0);
  REQUIRE(run(common + dir.file("b") + " --memory-budget 16 --stats-json " + dir.file("b.json"),
              dir.file("b.err")) == 0);
  CHECK(slurp(dir.file("b/pings.xtf")) == slurp(dir.file("a/pings.xtf")));
  const std::string a = slurp(dir.file("a.json")), b = slurp(dir.file("b.json"));
  const auto number = [](const std::string& json, const std::string& key) {
    const std::size_t at = json.find("\"" + key + "\": ");
    REQUIRE(at != std::string::npos);
    return std::stoull(json.substr(at + key.size() + 4));
  };
  INFO(a << b);
  CHECK(number(a, "budget_bytes") <= 192ull << 20);  // the default, in whole tiles
  CHECK(number(a, "budget_bytes") > 186ull << 20);
  CHECK(number(a, "evictions") == 0);
  CHECK(number(b, "budget_bytes") <= 16ull << 20);
  CHECK(number(b, "bytes") <= number(b, "budget_bytes"));
  CHECK(number(b, "evictions") > 0);
  CHECK(number(b, "tiles_made") > number(a, "tiles_made"));  // made again after eviction
  CHECK_THAT(slurp(dir.file("b.err")), Catch::Contains("seabed caches: heightmap"));
  // below 16 MB: refused, naming the option
  CHECK(run("run --memory-budget 8 --duration 1", dir.file("c.err")) == 2);
  CHECK_THAT(slurp(dir.file("c.err")), Catch::Contains("--memory-budget"));
}

TEST_CASE("run cli: bad input gets a clear error") {
  testing::TempDir dir("run-cli-bad");
  write_file(dir.file("s.yaml"), testing::small_scenario_yaml());
  const std::string s = dir.file("s.yaml");
  SECTION("a port in use") {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    REQUIRE(fd >= 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;
    REQUIRE(bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0);
    REQUIRE(listen(fd, 1) == 0);
    socklen_t len = sizeof a;
    getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
    const std::string port = std::to_string(ntohs(a.sin_port));
    CHECK(run("run " + s + " --can socketcand:127.0.0.1:" + port, dir.file("err")) == 1);
    const std::string err = slurp(dir.file("err"));
    INFO(err);
    CHECK(err.find("127.0.0.1:" + port) != std::string::npos);
    CHECK(err.find("in use") != std::string::npos);
    close(fd);
  }
  SECTION("a UDP pose port in use") {
    net::UdpReceiver taken(net::parse_host_port("127.0.0.1:0"));
    const std::string port = std::to_string(taken.bound_port());
    CHECK(run("run " + s + " --pose-from udp:127.0.0.1:" + port, dir.file("err")) == 1);
    const std::string err = slurp(dir.file("err"));
    INFO(err);
    CHECK(err.find("127.0.0.1:" + port) != std::string::npos);
    CHECK(err.find("in use") != std::string::npos);
  }
  SECTION("a ping that does not fit a datagram") {
    std::string y = testing::small_scenario_yaml();
    y.replace(y.find("max_range_m: 20"), 15, "max_range_m: 200");
    y.replace(y.find("bin_size_cm: 5"), 14, "bin_size_cm: 1");
    write_file(dir.file("big.yaml"), y);
    CHECK(run("run " + dir.file("big.yaml") + " --udp 127.0.0.1:9", dir.file("err")) == 1);
    const std::string err = slurp(dir.file("err"));
    INFO(err);
    CHECK(err.find("at most 16272 samples per side") != std::string::npos);
  }
  SECTION("usage errors") {
    CHECK(run("run " + s + " --rate fast") == 2);
    CHECK(run("run " + s + " --rate 0") == 2);
    CHECK(run("run " + s + " --udp nowhere") == 2);
    CHECK(run("run " + s + " --udp 127.0.0.1:0") == 2);
    CHECK(run("run " + s + " --threads 0") == 2);
    CHECK(run("run " + s + " --duration -1") == 2);
    CHECK(run("run " + s + " --stale-after 1") == 2);
    CHECK(run("run " + s + " --pose-from udp:127.0.0.1:5700 --rate max") == 2);
    CHECK(run("run " + s + " --bogus") == 2);
    CHECK(run("run " + s + " " + s) == 2);
    CHECK(run("run " + s + " --realtime-priority 0", dir.file("err")) == 2);
    CHECK(slurp(dir.file("err")).find("--realtime-priority") != std::string::npos);
    CHECK(run("run " + s + " --realtime-priority 100") == 2);
    CHECK(run("run " + s + " --lateness-tolerance-ms 0") == 2);
    CHECK(run("run " + s + " --lateness-tolerance-ms nan") == 2);
    CHECK(run("run " + s + " --can nonsense:spec", dir.file("err")) == 1);
    CHECK(slurp(dir.file("err")).find("nonsense:spec") != std::string::npos);
    CHECK(run("run " + s + " --imc 127.0.0.1:6001", dir.file("err")) == 2);
    CHECK(slurp(dir.file("err")).find("udp:HOST:PORT") != std::string::npos);
    CHECK(run("run " + s + " --imc udp:127.0.0.1:0") == 2);
    CHECK(run("run " + s + " --imc udp:127.0.0.1:6001 --imc-system 0") == 2);
    CHECK(run("run " + s + " --imc udp:127.0.0.1:6001 --imc-system 0x10000") == 2);
    CHECK(run("run " + s + " --imc-name auv", dir.file("err")) == 2);
    CHECK(slurp(dir.file("err")).find("--imc only") != std::string::npos);
  }
  SECTION("an absurd ping period, named with its allowed range") {
    // issue 11: 1e-9 s was accepted and `run --duration 2` never ended
    std::string y = testing::small_scenario_yaml();
    y.replace(y.find("bin_size_cm: 5"), 14, "bin_size_cm: 5\n  ping_period_s: 1e-9");
    write_file(dir.file("fast.yaml"), y);
    CHECK(run("run " + dir.file("fast.yaml") + " --duration 2", dir.file("err")) == 1);
    const std::string err = slurp(dir.file("err"));
    INFO(err);
    CHECK(err.find("sonar.ping_period_s: 1e-09 s is shorter than the two-way travel time") !=
          std::string::npos);
    CHECK(err.find("allowed: 0 (auto: 2 max_range_m / c), or 0.0267 .. 10 for max_range_m 20") !=
          std::string::npos);
  }
  SECTION("--stats-every is checked with --quiet too") {
    CHECK(run("run " + s + " --quiet --stats-every -1") == 2);
    CHECK(run("run " + s + " --quiet --stats-every nan", dir.file("err")) == 2);
    CHECK(slurp(dir.file("err")).find("'--stats-every': 'nan' is not a number") !=
          std::string::npos);
    CHECK(run("run " + s + " --stats-every inf") == 2);
  }
  SECTION("--stats-json into an unwritable place fails before the run, with the reason") {
    CHECK(run("run " + s + " --stats-json " + dir.file("no/such/dir/s.json") + " --record " +
                  dir.file("r"),
              dir.file("err")) == 1);
    const std::string err = slurp(dir.file("err"));
    INFO(err);
    CHECK(err.find("--stats-json " + dir.file("no/such/dir/s.json") +
                   ": cannot write: No such file or directory") != std::string::npos);
    CHECK(err.find("running") == std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir.file("r")));
  }
  SECTION("a missing scenario file") {
    CHECK(run("run " + dir.file("missing.yaml"), dir.file("err")) == 1);
    CHECK(slurp(dir.file("err")).find("missing.yaml") != std::string::npos);
  }
}
