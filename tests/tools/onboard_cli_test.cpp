// End-to-end onboard recognition, as a user runs it: a 5 cm model made with `sonarloop dataset`
// and `sonarloop train`, then the emulator on the default scenario with the onboard consumer
// in-process (`run --classify`), over UDP on 127.0.0.1 (`onboard --listen`), and on the
// recording (`onboard --xtf`). Every one of the four placed targets must be reported within 1 m
// of its true position with its class; at most kMaxFalseContacts other contacts.
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "autonomy/json_line.h"
#include "common/geodesy.h"
#include "config/loader/scenario_loader.h"
#include "drivers/imc/imc_codec.h"
#include "drivers/net/udp_receiver.h"
#include "sim/targets/target_type.h"
#include "tests/support/temp_dir.h"
#include "tests/tools/mcap_reader.h"
#include "tests/tools/sonarloop_cli.h"

using namespace sonarloop;

namespace {

using sonarloop::testing::kBinary;
using sonarloop::testing::run_logged;

const std::string kDefaultScenario = std::string(SONARLOOP_SOURCE_DIR) + "/config/default.yaml";
// Contacts farther than this from their target do not count as finding it (the brief's 1 m).
constexpr double kMaxPositionError_m = 1.0;
// Other contacts allowed: the default scenario's seabed has large clutter rocks (up to 0.8 m,
// 0.4 m tall) and relief that look like small objects; at the detector's default threshold
// (0.14 m) 7 are reported with this model, which has no clutter class and no contact gates (a
// survey-trained model's, `train --surveys`, keep most rocks out: docs/autonomy.md).
constexpr int kMaxFalseContacts = 10;
// The training set: 450 chips per class (1800 chips, about 30-45 s on 2 cores) at 5 cm on the
// scenario's own seabed, 8 aspect sectors. Measured on independent training sets (dataset seeds
// 201-205): 20 of 20 targets identified; with 300 per class 38 of 40 (seeds 101-110).
const std::string kDatasetArgs =
    " --count 450 --resolution-cm 5 --seed 1 --threads 2 --seabed " + kDefaultScenario;
const std::string kTrainArgs = " --aspect-sectors 8 --p 10";

using sonarloop::testing::slurp;

// The value of "key": in a flat JSON line (numbers, strings, true/false/null).
std::optional<std::string> json_value(const std::string& line, const std::string& key) {
  const std::string k = "\"" + key + "\":";
  const auto at = line.find(k);
  if (at == std::string::npos) return std::nullopt;
  std::size_t b = at + k.size();
  if (line[b] == '"') {
    const auto e = line.find('"', b + 1);
    return line.substr(b + 1, e - b - 1);
  }
  const auto e = line.find_first_of(",}", b);
  return line.substr(b, e - b);
}

struct Contact {
  Vec2 ne_m = Vec2::Zero();           // from latitude/longitude, in the scenario's plane
  Vec2 reported_ne_m = Vec2::Zero();  // its north_m / east_m
  std::string cls;
  bool mine_like = false;
};

std::vector<Contact> read_contacts(const std::string& path, const LocalTangentPlane& plane) {
  std::vector<Contact> out;
  std::istringstream in(slurp(path));
  std::string line;
  while (std::getline(in, line)) {
    const auto lat = json_value(line, "latitude_deg");
    const auto lon = json_value(line, "longitude_deg");
    REQUIRE(lat);
    REQUIRE(lon);
    Contact c;
    c.ne_m = plane.to_local(GeoPoint{std::stod(*lat), std::stod(*lon)});
    const auto north = json_value(line, "north_m");
    const auto east = json_value(line, "east_m");
    REQUIRE(north);
    REQUIRE(east);
    c.reported_ne_m = Vec2(std::stod(*north), std::stod(*east));
    c.cls = json_value(line, "class").value_or("");
    c.mine_like = json_value(line, "mine_like").value_or("") == "true";
    out.push_back(c);
  }
  return out;
}

// Checks the contacts against the scenario's targets; returns the number of false contacts.
int check_against_truth(const std::vector<Contact>& contacts, const config::Scenario& sc) {
  std::vector<bool> matched(contacts.size(), false);
  for (const scene::TargetDesc& t : sc.scene.targets) {
    const std::string key(targets::target_type_info(t.type).key);
    int found = 0;
    for (std::size_t i = 0; i < contacts.size(); ++i) {
      const double err = (contacts[i].ne_m - t.position_m).norm();
      if (err > kMaxPositionError_m) continue;
      matched[i] = true;
      ++found;
      INFO(key << " at (" << t.position_m.x() << ", " << t.position_m.y() << "): contact at ("
               << contacts[i].ne_m.x() << ", " << contacts[i].ne_m.y() << "), " << err
               << " m off, class " << contacts[i].cls);
      CHECK(contacts[i].cls == key);
      CHECK(contacts[i].mine_like);
    }
    INFO(key << " at (" << t.position_m.x() << ", " << t.position_m.y() << ")");
    CHECK(found == 1);  // one contact per object
  }
  return static_cast<int>(std::count(matched.begin(), matched.end(), false));
}

// Starts `sonarloop onboard --listen 127.0.0.1:0 ...` in the background; returns its pid and
// the port it printed.
std::pair<pid_t, int> start_listener(const testing::TempDir& dir, const std::string& model) {
  const std::string err = dir.file("listen.err");
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    std::freopen("/dev/null", "w", stdout);
    std::freopen(err.c_str(), "w", stderr);
    execl(kBinary.c_str(), kBinary.c_str(), "onboard", "--listen", "127.0.0.1:0", "--model",
          model.c_str(), "--contacts", dir.file("udp.jsonl").c_str(), "--idle-exit", "4",
          "--stats-json", dir.file("udp_stats.json").c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  const std::string marker = "listening on 127.0.0.1:";
  for (int k = 0; k < 500; ++k) {
    const std::string text = slurp(err);
    const auto at = text.find(marker);
    if (at != std::string::npos && text.find(' ', at + marker.size()) != std::string::npos) {
      return {pid, std::stoi(text.substr(at + marker.size()))};
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGTERM);
  waitpid(pid, nullptr, 0);
  FAIL("onboard --listen did not start: " << slurp(err));
  return {-1, 0};
}

long long stat_of(const std::string& json, const std::string& key) {
  return std::stoll(json_value(json, key).value_or("-1"));
}

}  // namespace

TEST_CASE("onboard cli: the default scenario's four targets, in-process, over UDP, from a file") {
  testing::TempDir dir("onboard-cli");
  const config::Scenario sc = config::load_scenario(kDefaultScenario);
  const LocalTangentPlane plane(
      GeoPoint{sc.scene.origin.latitude_deg, sc.scene.origin.longitude_deg});
  REQUIRE(sc.scene.targets.size() == 4);

  // the model: 5 cm highlight chips of the four classes
  const std::string chips = dir.file("chips");
  const std::string model = dir.file("atr.slpca");
  REQUIRE(run_logged(dir, "dataset --out " + chips + kDatasetArgs, "dataset") == 0);
  REQUIRE(run_logged(dir, "train " + chips + " --out " + model + kTrainArgs, "train") == 0);

  // 1. in-process: run --classify, as fast as possible (lossless), recording the pings; with
  // --imc the contacts also go out as IMC map features, counted by a receiver on its own thread
  net::UdpReceiver imc_rx(net::parse_host_port("127.0.0.1:0"), 1 << 20);
  // as root, a buffer beyond net.core.rmem_max, so that a descheduled reader loses nothing of the
  // pings sent at --rate max (best effort: without it only a weaker check is made below)
  const int want = 32 << 20;
  setsockopt(imc_rx.fd(), SOL_SOCKET, SO_RCVBUFFORCE, &want, sizeof want);
  int granted = 0;
  socklen_t len = sizeof granted;
  getsockopt(imc_rx.fd(), SOL_SOCKET, SO_RCVBUF, &granted, &len);
  std::atomic<bool> imc_done{false};
  std::atomic<int> imc_events{0}, imc_packets{0};
  std::thread imc_thread([&] {
    std::vector<std::uint8_t> buf(70000);
    while (!imc_done) {
      const auto d = imc_rx.receive(buf, 100);
      if (!d) continue;
      imc::Packet p;
      if (imc::decode(std::span<const std::uint8_t>(buf.data(), d->datagram_size), p) !=
          imc::DecodeStatus::kOk)
        continue;
      ++imc_packets;
      if (std::holds_alternative<imc::CcuEvent>(p.message)) ++imc_events;
    }
  });
  const std::string inproc = dir.file("inproc.jsonl");
  const int run_status =
      run_logged(dir,
                 "run " + kDefaultScenario + " --rate max --threads 2 --quiet --classify " + model +
                     " --contacts " + inproc + " --record " + dir.file("rec") + " --stats-json " +
                     dir.file("run_stats.json") +
                     " --imc udp:127.0.0.1:" + std::to_string(imc_rx.bound_port()),
                 "run");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  imc_done = true;
  imc_thread.join();
  REQUIRE(run_status == 0);
  const std::string run_err = slurp(dir.file("run.err"));
  INFO(run_err);
  CHECK_THAT(run_err, Catch::Contains("onboard: ") && Catch::Contains("lost 0") &&
                          Catch::Contains("ms per chip"));
  const std::vector<Contact> c1 = read_contacts(inproc, plane);
  const int false1 = check_against_truth(c1, sc);
  // north_m / east_m are in the scenario's frame (that of scene.json and truth.json): they
  // agree with the latitude/longitude to the rounding of the report (issue 10 §5)
  for (const Contact& c : c1)
    CHECK((c.reported_ne_m - c.ne_m).norm() < 0.01);
  WARN("run --classify: " << c1.size() << " contacts, " << false1 << " false");
  // every contact (they all have a position: the scenario's frame) as one IMC event
  CHECK(imc_packets > imc_events);  // the pings and the navigation too
  if (granted >= want) {
    CHECK(imc_events == static_cast<int>(c1.size()));
  } else {
    WARN("receive buffer " << granted << " bytes: IMC packets may be dropped, counts not compared");
    CHECK(imc_events > 0);
    CHECK(imc_events <= static_cast<int>(c1.size()));
  }
  CHECK(false1 <= kMaxFalseContacts);
  // the MCAP recording (rec/run.mcap) holds every contact, as the contacts file has it, on
  // /contacts, with its position on /contacts/fix, read by the independent reader (left out,
  // with the reason, where node or the npm registry is missing)
  if (const std::string why = testing::prepare_mcap_reader(); why.empty()) {
    REQUIRE(testing::read_mcap(dir.file("rec/run.mcap"), dir.file("mcap.jsonl"),
                               dir.file("mcap.err")) == 0);
    std::vector<std::string> recorded;
    std::size_t fixes = 0;
    std::ifstream in(dir.file("mcap.jsonl"));
    std::string line, error;
    while (std::getline(in, line)) {
      const auto j = autonomy::JsonLine::parse(line, error);
      REQUIRE(j);
      if (j->string("topic") == "/contacts") recorded.push_back(*j->string("data"));
      if (j->string("topic") == "/contacts/fix") {
        ++fixes;
        // at a contact's north_m / east_m
        const Vec2 ne = plane.to_local(GeoPoint{*j->number("latitude"), *j->number("longitude")});
        CHECK(std::any_of(c1.begin(), c1.end(),
                          [&](const Contact& c) { return (ne - c.reported_ne_m).norm() < 0.01; }));
      }
    }
    std::vector<std::string> written;
    std::ifstream contacts(inproc);
    while (std::getline(contacts, line))
      written.push_back(line);
    std::sort(recorded.begin(), recorded.end());
    std::sort(written.begin(), written.end());
    CHECK(recorded == written);
    CHECK(fixes == c1.size());
  } else {
    WARN("run.mcap's contacts not read: " << why);
  }

  // 2. the recording: the same pings give the same contacts, byte for byte
  const std::string from_file = dir.file("file.jsonl");
  REQUIRE(run_logged(dir,
                     "onboard --xtf " + dir.file("rec") + "/pings.xtf --model " + model +
                         " --contacts " + from_file,
                     "file") == 0);
  CHECK(slurp(from_file) == slurp(inproc));
  // --origin first-ping: the frame of recordings of no scenario. The default scenario's vehicle
  // starts at (-45, 0) (config/default.yaml), so every contact moves by the same offset, about
  // 45 m north (the first ping's navigation noise aside)
  const std::string first_ping = dir.file("first_ping.jsonl");
  REQUIRE(run_logged(dir,
                     "onboard --xtf " + dir.file("rec") + "/pings.xtf --model " + model +
                         " --origin first-ping --contacts " + first_ping,
                     "first_ping") == 0);
  const std::vector<Contact> c2 = read_contacts(first_ping, plane);
  REQUIRE(c2.size() == c1.size());
  REQUIRE_FALSE(c1.empty());
  const Vec2 offset = c2[0].reported_ne_m - c1[0].reported_ne_m;
  CHECK((offset - Vec2(45.0, 0.0)).norm() < 1.0);
  for (std::size_t i = 0; i < c2.size(); ++i)
    CHECK((c2[i].reported_ne_m - c1[i].reported_ne_m - offset).norm() < 0.02);

  // 3. over UDP on 127.0.0.1: onboard --listen, the emulator at 2x real time (with --rate
  // max's epoch, so that the ping times, and so the contacts, can be compared). 2x, not more:
  // CI machines are slow and shared (under ASan with other tests beside it a ping takes up to
  // 30 ms, and 5x real time is 13 ms a ping). The listener ends 4 s after the last datagram (the
  // emulator never pauses that long: late pings are dropped, not waited for).
  const auto [pid, port] = start_listener(dir, model);
  REQUIRE(run_logged(dir,
                     "run " + kDefaultScenario +
                         " --rate 2 --threads 2 --quiet --udp 127.0.0.1:" + std::to_string(port) +
                         " --epoch 1767225600 --stats-json " + dir.file("udp_run.json"),
                     "udp_run") == 0);
  int status = 0;
  bool exited = false;
  for (int k = 0; k < 600 && !exited; ++k) {  // --idle-exit 4: it ends on its own
    exited = waitpid(pid, &status, WNOHANG) == pid;
    if (!exited) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  if (!exited) {
    kill(pid, SIGTERM);
    waitpid(pid, &status, 0);
  }
  INFO(slurp(dir.file("listen.err")));
  REQUIRE(exited);
  REQUIRE(WIFEXITED(status));
  REQUIRE(WEXITSTATUS(status) == 0);
  const std::string udp_stats = slurp(dir.file("udp_stats.json"));
  const std::string run_stats = slurp(dir.file("udp_run.json"));
  const long long sent = stat_of(run_stats, "sent");  // pings.sent (pings.due: with dropped ones)
  const long long due = stat_of(run_stats, "due");
  const long long pings = stat_of(udp_stats, "pings");
  const long long lost = stat_of(udp_stats, "lost");
  INFO(udp_stats);
  CHECK(stat_of(udp_stats, "malformed") == 0);
  CHECK(pings <= sent);
  CHECK(pings + lost <= due);  // gaps: lost on the way, or never sent (deadline missed)
  REQUIRE(pings >= sent * 95 / 100);
  // nothing dropped by the emulator and nothing lost on the way: exactly the in-process
  // contacts (which were checked against the truth above). Pings the emulator dropped (a machine
  // too loaded even for 2x) make other chips: then only the delivery is checked.
  if (pings == sent && sent == due) {
    CHECK(slurp(dir.file("udp.jsonl")) == slurp(inproc));
  } else {
    WARN("the emulator dropped " << due - sent << " of " << due
                                 << " pings: contacts not compared with the truth");
  }
}

TEST_CASE("onboard cli: --imc sends each located contact as a map feature (a real recording)") {
  testing::TempDir dir("onboard-cli-imc");
  net::UdpReceiver rx(net::parse_host_port("127.0.0.1:0"), 1 << 20);
  const std::string xtf = std::string(SONARLOOP_SOURCE_DIR) + "/tests/data/xtf/scotsman-iver2.xtf";
  REQUIRE(run_logged(dir,
                     "onboard --xtf " + xtf + " --origin first-ping --contacts " +
                         dir.file("c.jsonl") + " --imc udp:127.0.0.1:" +
                         std::to_string(rx.bound_port()) + " --imc-system 0x2102",
                     "imc") == 0);
  std::size_t contacts = 0;
  {
    std::ifstream in(dir.file("c.jsonl"));
    std::string line;
    while (std::getline(in, line))
      contacts += line.find("\"latitude_deg\":") != std::string::npos;
  }
  REQUIRE(contacts > 0);
  std::vector<std::uint8_t> buf(70000);
  std::size_t events = 0;
  while (const auto d = rx.receive(buf, 500)) {
    imc::Packet p;
    REQUIRE(imc::decode(std::span<const std::uint8_t>(buf.data(), d->datagram_size), p) ==
            imc::DecodeStatus::kOk);
    CHECK(p.header.src == 0x2102);
    const auto& e = std::get<imc::CcuEvent>(p.message);
    REQUIRE(e.arg);
    CHECK(e.arg->id.rfind("c", 0) == 0);
    REQUIRE(e.arg->feature.size() == 1);
    // the recording's pings are at 48.4455 N, 68.8279 W (its first ping has no fix: 0, 0)
    CHECK(e.arg->feature[0].lat_rad * 180.0 / M_PI == Approx(48.4455).margin(0.002));
    CHECK(e.arg->feature[0].lon_rad * 180.0 / M_PI == Approx(-68.8279).margin(0.003));
    ++events;
  }
  CHECK(events == contacts);
  CHECK(run_logged(dir, "onboard --xtf " + xtf + " --imc 127.0.0.1:6001", "u") == 2);
  CHECK(run_logged(dir, "onboard --xtf " + xtf + " --imc-system 0x2000", "u") == 2);
}

TEST_CASE("onboard cli: usage errors") {
  testing::TempDir dir("onboard-cli-usage");
  CHECK(run_logged(dir, "onboard", "u") == 2);
  CHECK(run_logged(dir, "onboard --listen 127.0.0.1:0 --xtf x.xtf", "u") == 2);
  CHECK(run_logged(dir, "onboard --xtf x.xtf --idle-exit 2", "u") == 2);
  CHECK(run_logged(dir, "onboard --xtf " + dir.file("missing.xtf"), "u") == 1);
  CHECK(run_logged(dir, "onboard --listen 127.0.0.1:0 --model " + dir.file("missing.slpca"), "u") ==
        1);
  CHECK_THAT(slurp(dir.file("u.err")), Catch::Contains("missing.slpca"));
  CHECK(run_logged(dir, "run --contacts x.jsonl", "u") == 2);
  CHECK(run_logged(dir, "onboard --xtf x.xtf --origin 91,0", "u") == 2);
  CHECK_THAT(slurp(dir.file("u.err")), Catch::Contains("--origin: expected LAT,LON"));
  CHECK(run_logged(dir, "onboard --xtf x.xtf --origin 1,2 --scenario x.yaml", "u") == 2);
  // --stats-json into an unwritable place: refused at once, with the reason (issue 11)
  CHECK(run_logged(dir, "onboard --listen 127.0.0.1:0 --stats-json " + dir.file("no/dir/s.json"),
                   "u") == 1);
  CHECK_THAT(slurp(dir.file("u.err")),
             Catch::Contains("--stats-json " + dir.file("no/dir/s.json") +
                             ": cannot write: No such file or directory"));
  CHECK(run_logged(dir, "onboard --help", "u") == 0);
  CHECK_THAT(slurp(dir.file("u.out")), Catch::Contains("--listen") && Catch::Contains("examples"));
}
