// The autonomy loop end to end, as a user runs it: a small model made with `sonarloop dataset`
// and `sonarloop train`, then `sonarloop mission` on a two-target scenario, in lock-step (the
// default: one process, reproducible) and with --realtime (emulator, onboard consumer and agent
// as three processes; pings over UDP, contacts over UDP, navigation over a socketcand TCP
// connection, the pose over UDP, all on 127.0.0.1) in accelerated time. The re-look threshold is
// so high that every contact is uncertain: each must be re-looked from about 90 degrees at the
// pass range, and at least one object confirmed by its looks. In lock-step the report is the
// same byte for byte on one render thread or two, paced or not, and the survey is scored. Then
// Ctrl-C: the mission still writes its report; SIGKILL: its processes end with it; an agent that
// fails: the mission fails with the agent's reason, never scoring an earlier run's report.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "autonomy/json_line.h"
#include "tests/support/temp_dir.h"
#include "tests/tools/sonarloop_cli.h"

using namespace sonarloop;
using sonarloop::autonomy::JsonLine;
using sonarloop::testing::slurp;

namespace {

using sonarloop::testing::kBinary;
using sonarloop::testing::run_logged;

const std::string kTwoTargetsScenario =
    std::string(SONARLOOP_SOURCE_DIR) + "/tests/data/autonomy/two_targets.yaml";
// The scenario's one survey line and its surroundings (see the scenario's header).
const std::string kArea = "-40,-20,40,20";
// Accelerated time for --realtime: about 400 s of mission in two and a half minutes. Real time
// drops a ping rendered late, and the detector needs neighbouring pings: under the sanitizer on
// 2 cores busy with other tests, rate 6 once gave no contact at all.
const std::string kRate = "3";
constexpr double kAspectToleranceDeg = 10.0;  // of the 90 degrees
constexpr double kPassRange_m = 25.0;         // the agent's default
constexpr double kPassRangeTolerance_m = 3.0;

// A two-class model (the scenario's types), 150 chips each on flat sand: a few seconds.
std::string train_model(const testing::TempDir& dir) {
  REQUIRE(
      run_logged(dir,
                 "dataset --out " + dir.file("chips") +
                     " --count 150 --resolution-cm 5 --seed 1 --threads 2 --seabed flat --classes "
                     "manta,cylinder",
                 "dataset") == 0);
  const std::string model = dir.file("atr.slpca");
  REQUIRE(run_logged(
              dir, "train " + dir.file("chips") + " --out " + model + " --aspect-sectors 4 --p 10",
              "train") == 0);
  return model;
}

// The model, made once per run of this file's cases and shared by them (they only read it).
const std::string& shared_model() {
  static const testing::TempDir dir("mission_model");
  static const std::string model = train_model(dir);
  return model;
}

JsonLine parse_file(const std::string& path) {
  std::string error;
  const auto j = JsonLine::parse(slurp(path), error);
  INFO(path << ": " << error);
  REQUIRE(j);
  return *j;
}

}  // namespace

namespace {

// The re-looks of a mission report: each flown passes at ~90 degrees and the pass range and sees
// its object again, and an object is confirmed by its looks.
void check_relooks(const JsonLine& m) {
  const JsonLine agent = *m.object("agent");
  CHECK(agent.boolean("mission_done") == true);
  CHECK(agent.number("contacts_received").value_or(0) >= 2);
  CHECK(m.object("summary")->number("detected") == Approx(2));
  const auto relooks = agent.objects("relooks");
  REQUIRE(!relooks.empty());
  int passed = 0;
  for (const JsonLine& r : relooks) {
    if (!r.boolean("passed").value_or(false)) continue;
    ++passed;
    CHECK(r.number("aspect_change_deg").value_or(0) == Approx(90.0).margin(kAspectToleranceDeg));
    CHECK(r.number("pass_range_m").value_or(0) ==
          Approx(kPassRange_m).margin(kPassRangeTolerance_m));
    CHECK(r.boolean("second_look") == true);
    CHECK(r.number("latency_s").value_or(-1) > 0.0);
  }
  CHECK(passed >= 1);
  int confirmed_after_relook = 0;
  for (const JsonLine& o : agent.objects("objects")) {
    if (o.boolean("relooked") == true && o.string("state") == "confirmed" &&
        o.number("looks").value_or(0) >= 2) {
      ++confirmed_after_relook;
    }
  }
  CHECK(confirmed_after_relook >= 1);
}

}  // namespace

TEST_CASE("lock-step: re-looks flown; the same report on 1 or 2 threads, paced or not; scored") {
  testing::TempDir dir("mission_lockstep");
  const std::string& model = shared_model();
  const std::string base = "mission " + kTwoTargetsScenario + " --model " + model +
                           " --threshold 1e6 --area " + kArea + " --detector-threshold 0.12" +
                           " --relook-budget none --quiet";
  REQUIRE(run_logged(
              dir, base + " --threads 1 --report " + dir.file("a.json") + " --out " + dir.file("a"),
              "a") == 0);
  REQUIRE(run_logged(dir,
                     base + " --threads 2 --rate 40 --report " + dir.file("new/b.json") +
                         " --out " + dir.file("b"),
                     "b") == 0);
  INFO(slurp(dir.file("a.err")));
  const std::string a = slurp(dir.file("a.json"));
  CHECK(a == slurp(dir.file("new/b.json")));  // the report's folder made as --out's
  CHECK(slurp(dir.file("a/seed_3_contacts.jsonl")) == slurp(dir.file("b/seed_3_contacts.jsonl")));
  const JsonLine m = parse_file(dir.file("a.json"));
  CHECK(m.object("run")->string("mode") == "lockstep");
  const auto missions = m.objects("missions");
  REQUIRE(missions.size() == 1);
  check_relooks(missions[0]);
  CHECK(missions[0].object("agent")->string("mode") == "lockstep");
  // the pooled summary: of the one seed, the seed's
  const auto pooled = m.object("summary");
  REQUIRE(pooled);
  CHECK(pooled->number("targets") == missions[0].object("summary")->number("targets"));
  CHECK(pooled->number("mission_time_s") ==
        missions[0].object("summary")->number("mission_time_s"));
  CHECK(pooled->boolean("mission_done") == missions[0].object("summary")->boolean("mission_done"));
  // the survey's score: both targets covered and found
  const auto rows = m.objects("survey");
  REQUIRE(!rows.empty());
  CHECK(rows[0].string("scope") == "all");
  CHECK(rows[0].number("covered") == Approx(2));
  CHECK(rows[0].number("detected") == Approx(2));
  const std::string csv = slurp(dir.file("a/survey.csv"));
  CHECK(csv.rfind("scope,surveys,targets,covered,detected,pd", 0) == 0);
  CHECK(csv.find("\nall,1,2,2,2,1.0000") != std::string::npos);
  CHECK(slurp(dir.file("a/detector_froc.csv")).rfind("threshold,targets", 0) == 0);
  CHECK(slurp(dir.file("a/survey_targets.csv")).find("manta") != std::string::npos);
  // --match-radius: the survey's score and the agent's objects both match within it (a contact
  // lies some centimetres from its target: at 1 cm both are missed by both alike)
  REQUIRE(run_logged(dir,
                     base + " --no-relook --match-radius 0.01 --report " + dir.file("c.json") +
                         " --out " + dir.file("c"),
                     "c") == 0);
  const JsonLine c = parse_file(dir.file("c.json"));
  const auto c_rows = c.objects("survey");
  REQUIRE(!c_rows.empty());
  const double c_detected = c_rows[0].number("detected").value_or(-1);
  CHECK(c_detected == Approx(0));
  CHECK(c.object("summary")->number("detected") == Approx(c_detected));
}

TEST_CASE("lock-step: Ctrl-C stops the mission and still writes the report") {
  testing::TempDir dir("mission_lockstep_stop");
  const std::string& model = shared_model();
  const std::string report = dir.file("mission.json");
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    std::freopen(dir.file("mission.err").c_str(), "w", stderr);
    // paced at real time: the survey would take a minute
    execl(kBinary.c_str(), kBinary.c_str(), "mission", kTwoTargetsScenario.c_str(), "--model",
          model.c_str(), "--rate", "1", "--area", kArea.c_str(), "--report", report.c_str(),
          "--out", dir.file("out").c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::seconds(3));
  kill(pid, SIGINT);
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  INFO(slurp(dir.file("mission.err")));
  CHECK(WIFEXITED(status));
  const JsonLine m = parse_file(report);
  CHECK(m.object("run")->boolean("stopped") == true);
  const auto missions = m.objects("missions");
  REQUIRE(missions.size() == 1);
  CHECK(missions[0].object("agent")->boolean("stopped") == true);
  CHECK(missions[0].object("summary")->number("mission_time_s").value_or(0) > 0.0);
}

TEST_CASE(
    "--realtime: an uncertain contact is re-looked from ~90 degrees and confirmed, over loopback",
    "[realtime]") {
  testing::TempDir dir("mission_cli");
  const std::string& model = shared_model();
  const std::string report = dir.file("mission.json");
  const int rc = run_logged(dir,
                            "mission " + kTwoTargetsScenario + " --realtime --model " + model +
                                " --rate " + kRate + " --threshold 1e6 --area " + kArea +
                                " --detector-threshold 0.12 --relook-timing immediate --report " +
                                report + " --out " + dir.file("logs") + " --quiet",
                            "mission");
  INFO(slurp(dir.file("mission.err"))
       << slurp(dir.file("logs/agent.log")) << slurp(dir.file("logs/emulator.log"))
       << slurp(dir.file("logs/onboard.log")));
  REQUIRE(rc == 0);
  const JsonLine m = parse_file(report);
  // navigation came over CAN (socketcand), with the seabed's depth for the altitude keeping
  const JsonLine nav = *m.object("agent")->object("nav");
  CHECK(nav.number("frames").value_or(0) > 100);
  CHECK(nav.number("depth_updates").value_or(0) > 10);
  check_relooks(m);
}

namespace {

// Starts `mission --realtime` in `dir` (report mission.json, logs in logs/, stderr to
// mission.err); returns its pid once its agent flies (nav connected), and whether it did.
std::pair<pid_t, bool> start_flying_mission(const testing::TempDir& dir) {
  const std::string& model = shared_model();
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    std::freopen(dir.file("mission.err").c_str(), "w", stderr);
    execl(kBinary.c_str(), kBinary.c_str(), "mission", kTwoTargetsScenario.c_str(), "--realtime",
          "--model", model.c_str(), "--rate", kRate.c_str(), "--area", kArea.c_str(), "--report",
          dir.file("mission.json").c_str(), "--out", dir.file("logs").c_str(), "--quiet",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  bool flying = false;
  for (int k = 0; k < 1200 && !flying; ++k) {
    flying = slurp(dir.file("logs/agent.log")).find("nav connected") != std::string::npos;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return {pid, flying};
}

}  // namespace

TEST_CASE("--realtime: Ctrl-C stops the mission's three processes and still writes the report",
          "[realtime]") {
  testing::TempDir dir("mission_stop");
  const std::string report = dir.file("mission.json");
  // once the agent flies (nav connected), interrupt
  const auto [pid, flying] = start_flying_mission(dir);
  std::this_thread::sleep_for(std::chrono::seconds(2));
  kill(pid, SIGINT);
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  INFO(slurp(dir.file("mission.err")));
  CHECK(flying);
  CHECK(WIFEXITED(status));
  const JsonLine m = parse_file(report);
  CHECK(m.object("run")->boolean("stopped") == true);
  CHECK(m.object("agent")->boolean("stopped") == true);
  CHECK(m.object("summary")->number("mission_time_s").value_or(0) > 0.0);
}

TEST_CASE("--realtime: the agent's failure is the mission's, with its reason; no stale report",
          "[realtime]") {
  testing::TempDir dir("mission_fail");
  const std::string& model = shared_model();
  // an earlier run's agent report in the same --out: it must not be scored as this run's
  std::filesystem::create_directories(dir.file("logs"));
  { std::ofstream(dir.file("logs/agent.json")) << R"({"stale": true})"; }
  const int rc =
      run_logged(dir,
                 "mission " + kTwoTargetsScenario + " --realtime --model " + model + " --rate " +
                     kRate + " --line-spacing 0.001 --report " + dir.file("mission.json") +
                     " --out " + dir.file("logs") + " --quiet",
                 "mission");
  const std::string err = slurp(dir.file("mission.err"));
  INFO(err);
  CHECK(rc == 1);
  // the agent's own reason, in the mission's message and report
  CHECK_THAT(err, Catch::Contains("agent wrote no report (status 2: ") &&
                      Catch::Contains("--line-spacing"));
  const JsonLine m = parse_file(dir.file("mission.json"));
  CHECK_THAT(m.string("error").value_or(""), Catch::Contains("--line-spacing"));
  CHECK_FALSE(std::filesystem::exists(dir.file("logs/agent.json")));
}

namespace {

// The processes whose parent is `pid` (from /proc).
std::vector<pid_t> children_of(pid_t pid) {
  std::vector<pid_t> out;
  for (const auto& e : std::filesystem::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string stat = slurp(e.path().string() + "/stat");
    // pid (comm) state ppid ...: after the last ')'
    const auto close = stat.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(stat.substr(close + 1));
    char state = 0;
    pid_t ppid = 0;
    rest >> state >> ppid;
    if (ppid == pid) out.push_back(static_cast<pid_t>(std::stoi(name)));
  }
  return out;
}

// Whether `pid` has ended (gone, or a zombie nobody reaped yet).
bool ended(pid_t pid) {
  const std::string stat = slurp("/proc/" + std::to_string(pid) + "/stat");
  const auto close = stat.rfind(')');
  return close == std::string::npos || stat.substr(close + 2, 1) == "Z";
}

}  // namespace

TEST_CASE("--realtime: SIGKILL of the mission ends its three processes too", "[realtime]") {
  testing::TempDir dir("mission_kill");
  const auto [pid, flying] = start_flying_mission(dir);
  const std::vector<pid_t> children = children_of(pid);
  INFO(slurp(dir.file("mission.err")));
  CHECK(flying);
  REQUIRE(children.size() == 3);
  kill(pid, SIGKILL);
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  // each child got SIGTERM from the kernel when its parent died, and stops cleanly
  for (pid_t c : children) {
    bool gone = false;
    for (int k = 0; k < 200 && !gone; ++k) {
      gone = ended(c);
      if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    CHECK(gone);
    if (!gone) kill(c, SIGKILL);
  }
}
