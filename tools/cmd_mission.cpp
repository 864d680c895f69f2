// sonarloop mission: the whole autonomy loop for a scenario — by default in lock-step in this
// process (mission/lockstep.h: reproducible, scored against the truth over any number of seeds),
// or with --realtime as three child processes of this binary on loopback: the emulator (`run`),
// the onboard consumer (`onboard`) and the agent (`autonomy`); then a summary and a JSON report
// (mission/mission_report.h).
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "atr/contact.h"
#include "drivers/json/json_writer.h"
#include "drivers/net/unique_fd.h"
#include "mission/default_model.h"
#include "mission/mission_report.h"
#include "tools/args.h"
#include "tools/cli_helpers.h"
#include "tools/cmd_mission_lockstep.h"
#include "tools/commands.h"
#include "tools/output_file.h"
#include "tools/scenario_source.h"

namespace sonarloop::tools {
namespace {

// After the agent ends, how long the emulator and the onboard consumer get to stop on SIGINT.
constexpr double kStopGraceS = 15.0;
constexpr auto kPoll = std::chrono::milliseconds(100);

// A free port on 127.0.0.1 for `type` (SOCK_DGRAM, SOCK_STREAM): bound to port 0 and released
// (a small window in which another program could take it).
int free_port(int type) {
  net::UniqueFd fd(::socket(AF_INET, type, 0));
  if (!fd.valid()) throw std::runtime_error("socket: " + net::errno_text(errno));
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  if (::bind(fd.get(), reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::getsockname(fd.get(), reinterpret_cast<sockaddr*>(&a), &len) != 0) {
    throw std::runtime_error("cannot find a free port: " + net::errno_text(errno));
  }
  return ntohs(a.sin_port);
}

struct Child {
  std::string name;
  pid_t pid = -1;
  int status = -1;  // exit status once ended
  bool running() const { return pid > 0 && status < 0; }
};

// Starts this binary with `args`, stdout and stderr to `log`, in its own process group (so a
// terminal's Ctrl-C reaches only the mission, which forwards it once). The child gets SIGTERM
// when the mission dies, however it dies (SIGKILL too: PR_SET_PDEATHSIG), and stops cleanly: no
// emulator is left following a pose that never comes.
Child spawn(const std::string& name, const std::vector<std::string>& args, const std::string& log) {
  std::vector<char*> argv;
  std::string self = "/proc/self/exe";
  argv.push_back(self.data());
  std::vector<std::string> copy = args;
  for (auto& a : copy)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork: " + net::errno_text(errno));
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) _exit(128 + SIGTERM);  // the mission died before the line above
    ::setpgid(0, 0);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      ::close(fd);
    }
    ::execv("/proc/self/exe", argv.data());
    _exit(127);
  }
  return Child{name, pid, -1};
}

void reap(Child& c) {
  if (!c.running()) return;
  int st = 0;
  if (::waitpid(c.pid, &st, WNOHANG) == c.pid) c.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128;
}

// SIGINT, then up to grace_s for it to end, then SIGKILL.
void stop(Child& c, double grace_s) {
  if (!c.running()) return;
  ::kill(c.pid, SIGINT);
  const auto until = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(grace_s));
  while (c.running() && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(kPoll);
    reap(c);
  }
  if (c.running()) {
    std::fprintf(stderr, "mission: %s did not stop in %.0f s: killed\n", c.name.c_str(), grace_s);
    ::kill(c.pid, SIGKILL);
    int st = 0;
    ::waitpid(c.pid, &st, 0);
    c.status = 137;
  }
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Why a child failed, as its log says: its last line with "error:" (else its last line, but for
// a usage error's "(see ... --help)").
std::string child_reason(const std::string& log) {
  std::istringstream in(read_file(log));
  std::string line, last, error;
  while (std::getline(in, line)) {
    if (line.empty() || line.rfind("(see ", 0) == 0) continue;
    last = line;
    if (line.find("error:") != std::string::npos) error = line;
  }
  return error.empty() ? last : error;
}

// "NAME ended (status S: REASON; see LOG)"
std::string child_failure(const Child& c, const std::string& log, const std::string& what) {
  const std::string reason = child_reason(log);
  return c.name + " " + what + " (status " + std::to_string(c.status) +
         (reason.empty() ? "" : ": " + reason) + "; see " + log + ")";
}

std::string loopback(int port) {
  return "127.0.0.1:" + std::to_string(port);
}

// The mission's ports on 127.0.0.1, each free when chosen.
struct Ports {
  int sonar = free_port(SOCK_DGRAM);     // emulator -> onboard: XTF datagrams
  int contacts = free_port(SOCK_DGRAM);  // onboard -> agent: contact reports
  int pose = free_port(SOCK_DGRAM);      // agent -> emulator: the vehicle's pose
  int can = free_port(SOCK_STREAM);      // emulator -> agent: navigation (socketcand)
};

// Where the children's logs and files go (--out).
struct Logs {
  std::string dir;
  std::string path(const std::string& name) const {
    return (std::filesystem::path(dir) / name).string();
  }
};

std::vector<std::string> onboard_args(const Args& args, const std::string& model,
                                      const Ports& ports, const Logs& logs,
                                      const std::vector<std::string>& scenario_args) {
  std::vector<std::string> onboard = {"onboard",
                                      "--listen",
                                      loopback(ports.sonar),
                                      "--model",
                                      model,
                                      "--contacts",
                                      "udp:" + loopback(ports.contacts),
                                      "--stats-json",
                                      logs.path("onboard_stats.json")};
  onboard.insert(onboard.end(), scenario_args.begin(), scenario_args.end());
  for (const char* option : {"--detector-threshold", "--gate-threshold"}) {
    if (const auto v = args.get(option)) {
      onboard.push_back(option);
      onboard.push_back(*v);
    }
  }
  return onboard;
}

std::vector<std::string> emulator_args(const std::optional<std::string>& scenario_path,
                                       const std::string& rate, const Ports& ports,
                                       const Logs& logs) {
  std::vector<std::string> emulator = {"run"};
  if (scenario_path) emulator.push_back(*scenario_path);
  for (const std::string& a :
       {std::string("--udp"), loopback(ports.sonar), std::string("--can"),
        "socketcand:" + loopback(ports.can), std::string("--pose-from"),
        "udp:" + loopback(ports.pose), std::string("--rate"), rate, std::string("--stats-every"),
        std::string("10"), std::string("--stats-json"), logs.path("emulator_stats.json")})
    emulator.push_back(a);
  return emulator;
}

// The agent's arguments: the wiring, then the mission's options that are the agent's.
std::vector<std::string> agent_args(const Args& args, const std::string& rate, const Ports& ports,
                                    const Logs& logs,
                                    const std::vector<std::string>& scenario_args) {
  std::vector<std::string> agent = {"autonomy",
                                    "--contacts",
                                    "udp:" + loopback(ports.contacts),
                                    "--nav",
                                    "socketcand:" + loopback(ports.can),
                                    "--pose-to",
                                    "udp:" + loopback(ports.pose),
                                    "--rate",
                                    rate,
                                    "--report",
                                    logs.path("agent.json")};
  agent.insert(agent.end(), scenario_args.begin(), scenario_args.end());
  for (const char* o : {"--threshold", "--line-spacing", "--pass-range", "--max-duration", "--area",
                        "--area-margin", "--max-relooks", "--relook-timing", "--relook-budget"}) {
    if (const auto v = args.get(o)) {
      agent.push_back(o);
      agent.push_back(*v);
    }
  }
  if (args.has("--no-relook")) agent.push_back("--no-relook");
  if (args.has("--relook-all")) agent.push_back("--relook-all");
  return agent;
}

// Waits for the agent (children[2]) to end. A child that ends early, or a stop request, stops the
// agent (SIGINT, once); progress every 10 s unless quiet. Returns what failed ("" if nothing).
std::string supervise(std::vector<Child>& children, const Logs& logs, bool quiet) {
  Child& agent_child = children[2];
  const auto t0 = std::chrono::steady_clock::now();
  auto next_progress = t0 + std::chrono::seconds(10);
  bool forwarded = false;
  std::string failure;
  for (;;) {
    std::this_thread::sleep_for(kPoll);
    for (Child& c : children)
      reap(c);
    if (!agent_child.running()) break;
    for (const Child& c : children) {
      if (&c != &agent_child && !c.running() && failure.empty()) {
        failure = child_failure(c, logs.path(c.name + ".log"), "ended early");
      }
    }
    if (!failure.empty() && !forwarded) {
      std::fprintf(stderr, "mission: %s: stopping\n", failure.c_str());
      ::kill(agent_child.pid, SIGINT);
      forwarded = true;
    }
    if (stop_requested() && !forwarded) {
      std::fprintf(stderr, "mission: stop requested: stopping the agent, then the others\n");
      ::kill(agent_child.pid, SIGINT);
      forwarded = true;
    }
    if (!quiet && std::chrono::steady_clock::now() >= next_progress) {
      next_progress += std::chrono::seconds(10);
      std::fprintf(stderr, "mission: %.0f s wall ...\n",
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
  }
  return failure;
}

// The report's "run" object: how the mission was run.
std::string run_settings_json(const Args& args, const config::Scenario& scenario,
                              const std::string& rate, const std::string& model,
                              const std::string& failure) {
  json::Writer settings;
  settings.begin_object();
  settings.field("scenario", scenario.scene.name).field("rate", rate);
  settings.field("relooks", !args.has("--no-relook"));
  settings.field("relook_all", args.has("--relook-all"));
  settings.field("model", model).field("stopped", stop_requested() || !failure.empty());
  settings.field("failure", failure);
  settings.end_object();
  return settings.str();
}

// --realtime: the three processes on loopback (the code above).
int run_realtime(const Args& args, const std::string& model,
                 const std::optional<std::string>& scenario_path,
                 const config::Scenario& scenario) {
  const std::string rate = args.get_or("--rate", "10");
  args.get_double("--rate", 0.01, 1000.0);  // validated here, used by the children
  args.get_double("--gate-threshold", 0.0, 1.0);
  const std::string report_path = args.get_or("--report", "out/mission.json");
  const Logs logs{args.get_or(
      "--out", (std::filesystem::path(report_path).parent_path() / "mission_logs").string())};
  make_folder("--report", std::filesystem::path(report_path).parent_path());
  make_folder("--out", logs.dir);
  OutputFile report("--report", report_path);  // opened now: fails before the run
  const bool quiet = args.has("--quiet");

  // set up: the three children's command lines, wired on loopback; no report of an earlier run
  // in --out may be taken for this one's
  std::error_code ec;
  std::filesystem::remove(logs.path("agent.json"), ec);
  if (ec) {
    throw std::runtime_error("cannot remove the earlier run's " + logs.path("agent.json") + ": " +
                             ec.message());
  }
  const Ports ports;
  std::vector<std::string> scenario_args;
  if (scenario_path) scenario_args = {"--scenario", *scenario_path};
  const std::vector<std::string> onboard = onboard_args(args, model, ports, logs, scenario_args);
  const std::vector<std::string> emulator = emulator_args(scenario_path, rate, ports, logs);
  const std::vector<std::string> agent = agent_args(args, rate, ports, logs, scenario_args);

  // run: until the agent ends, then stop the others
  install_stop_flag();
  std::fprintf(stderr,
               "mission: scenario '%s', real time x %s, re-looks %s; logs in %s (onboard.log, "
               "emulator.log, agent.log)\n",
               scenario.scene.name.c_str(), rate.c_str(), args.has("--no-relook") ? "off" : "on",
               logs.dir.c_str());
  std::vector<Child> children;
  children.push_back(spawn("onboard", onboard, logs.path("onboard.log")));
  children.push_back(spawn("emulator", emulator, logs.path("emulator.log")));
  children.push_back(spawn("agent", agent, logs.path("agent.log")));
  const std::string failure = supervise(children, logs, quiet);
  for (Child& c : children)
    stop(c, kStopGraceS);

  // report
  const std::string agent_report = read_file(logs.path("agent.json"));
  if (agent_report.empty()) {
    const std::string why = child_failure(children[2], logs.path("agent.log"), "wrote no report") +
                            (failure.empty() ? "" : "; " + failure);
    std::fprintf(stderr, "mission: %s\n", why.c_str());
    json::Writer w;
    w.begin_object().field("error", why).end_object();
    report.write_and_close(w.str() + "\n");
    return 1;
  }
  mission::MissionSummary s;
  report.write_and_close(mission::mission_report_json(
      agent_report, scenario, "\"run\": " + run_settings_json(args, scenario, rate, model, failure),
      &s));
  mission::print_mission_summary(s);
  std::fprintf(stderr, "mission: report %s\n", report_path.c_str());
  return failure.empty() ? 0 : 1;
}

// The seeds: --seed S (default the scenario's) and the --seeds N after it.
int run_mission(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--model"},
                         {"--realtime", false},
                         {"--rate"},
                         {"--seed"},
                         {"--seeds"},
                         {"--threads"},
                         {"--match-radius"},
                         {"--layout"},
                         {"--classify-candidates", false},
                         {"--detector-threshold"},
                         {"--gate-threshold"},
                         {"--threshold"},
                         {"--no-relook", false},
                         {"--relook-all", false},
                         {"--report"},
                         {"--out"},
                         {"--line-spacing"},
                         {"--pass-range"},
                         {"--area"},
                         {"--area-margin"},
                         {"--max-relooks"},
                         {"--relook-timing"},
                         {"--relook-budget"},
                         {"--max-duration"},
                         {"--quiet", false}});
  if (args.positionals().size() > 1) throw UsageError("expected at most one SCENARIO.yaml");
  std::optional<std::string> model = args.get("--model");
  if (model && !mission::is_default_model(*model) && !std::filesystem::exists(*model)) {
    throw UsageError("--model " + *model + ": no such file");
  }
  const std::optional<std::string> scenario_path =
      args.positionals().empty() ? std::nullopt : std::optional(args.positionals()[0]);
  const config::Scenario scenario = load_scenario_or_default(scenario_path);
  if (!model || mission::is_default_model(*model)) {
    install_stop_flag();
    model = mission::ensure_default_model(args.has("--quiet"), [] { return stop_requested(); });
    std::fprintf(stderr, "mission: the default model, %s\n", model->c_str());
  }
  if (args.has("--realtime")) {
    for (const char* o : {"--seed", "--seeds", "--threads", "--match-radius", "--layout",
                          "--classify-candidates"}) {
      if (args.has(o))
        throw UsageError(std::string(o) + " applies to lock-step missions, not --realtime");
    }
    return run_realtime(args, *model, scenario_path, scenario);
  }
  return run_lockstep_missions(args, *model, scenario);
}

}  // namespace

const Command kMissionCommand{
    "mission", "the autonomy loop for a scenario: emulator + onboard + agent, scored, over seeds",
    R"(usage: sonarloop mission [SCENARIO.yaml | NAME] [--model MODEL] [options]

Flies the whole loop of docs/autonomy.md: the emulator renders each ping from where the example
agent steers, the onboard consumer detects and classifies, the agent surveys the scenario's area
(a lawnmower) and re-looks the contacts it is unsure of. Then what the vehicle received, the
contact stream, is scored against the scenario's truth (docs/autonomy.md, "Survey scoring"):
probability of detection of the targets the swath covered, identification and mine / non-mine of
those detected, false contacts per km² and per target, per seabed kind and per target type with
95 % Wilson intervals, and the detector's FROC from every candidate it considered.

Lock-step (the default): the emulator's renderer, the onboard consumer and the agent run in this
process, advanced together in simulation time (mission/lockstep.h): no ping is ever dropped, and
the report is a function of the scenario, the seed and the options only, the same at any --rate,
on any number of threads and on a loaded machine. Several seeds (--seeds N) fly the same survey
over N realisations of the seabed, its rocks, the speckle and the navigation errors; --layout
random also draws the targets afresh per seed (surveys a model was not tuned on).

--realtime: the same loop as three child processes of this binary on 127.0.0.1 (free ports),
each on the wall clock as a vehicle's would be: the emulator (`run SCENARIO --pose-from udp:..
--udp .. --can socketcand:..`), the onboard consumer (`onboard --listen .. --contacts udp:..`)
and the agent (`autonomy`); their output goes to DIR/NAME.log. Not reproducible: when a pose
reaches the emulator and a contact the agent depend on the scheduler, and a ping rendered late
is dropped. One seed, the agent's objects scored.

Writes the JSON report (--report) and, in lock-step, into --out DIR: survey.csv (the pooled
table), survey_targets.csv (every target of every seed), survey_false_contacts.csv,
detector_froc.csv (detection against false contacts over the detector's threshold),
gate_froc.csv (over the contact gate's, with a model that has one), and per seed
seed_S_contacts.jsonl (the contact stream), seed_S_candidates.csv (every detector candidate
with its fate and features) and seed_S_agent.log (the agent's decisions). Ctrl-C (or SIGTERM)
stops the mission and still writes the report ("stopped": true).

options:
  --model MODEL          the onboard consumer's model (`sonarloop train`); default (or none
                         given): the default model, trained once from the documented recipe on
                         the built-in survey scenarios and cached (mission/default_model.h; about
                         6 minutes on 2 cores the first time)
  --seeds N              lock-step: fly N seeds (default 1), from --seed S (default: the
                         scenario's seed)
  --layout L             lock-step: scenario (the scenario's targets, default) or random (the
                         same types drawn anywhere in the survey area, 25 m apart, per seed)
  --threads N            lock-step: render threads (default: all cores)
  --rate X               lock-step: pace the loop at X times real time (default: as fast as it
                         renders; the report does not change). --realtime: the children's rate
                         (default 10)
  --realtime             the three processes on the wall clock (see above)
  --detector-threshold H the detector's operating threshold, the smallest object height in
                         metres measured from its shadow (default 0.14; atr/detector.h)
  --gate-threshold P     the classification gate's operating point, the target probability a
                         detection needs (0 to 1; default: the model's): higher gives fewer
                         false contacts and fewer targets (gate_froc.csv in --out)
  --classify-candidates  lock-step: classify the detector's candidates below its threshold too
                         (in seed_S_candidates.csv; slower)
  --match-radius M       lock-step: a contact within M of a target is it (default 3; more
                         where the navigation drifts: contacts are placed from it)
  --threshold T          the agent's re-look margin threshold (default 0.05)
  --no-relook            survey only (the baseline of the table)
  --relook-all           re-look non-mine objects too (default: only where the doubt could
                         change the mine / non-mine decision; see sonarloop autonomy --help)
  --relook-timing T      after-survey (default: the survey first, then the objects still
                         uncertain, cheapest to reach first) or immediate (each at once, the
                         survey cut and resumed)
  --relook-budget F      after the survey, re-looks take at most F times the survey's planned
                         time (default 0.5: the mission at most 1.5 times the survey); none: no
                         limit
  --max-relooks N        the agent's re-look budget in re-looks (default: no limit)
  --line-spacing M       lawnmower line spacing (default 40)
  --pass-range M         re-look pass range (default 25)
  --area N0,E0,N1,E1     the survey rectangle (default: the seabed less --area-margin)
  --area-margin M        (default 50)
  --max-duration S       stop the agent after S mission seconds
  --report FILE          the JSON report (default out/mission.json; its folder is made)
  --out DIR              lock-step: the tables and per-seed files (default: FILE's
                         folder/mission); --realtime: the children's logs and reports (default:
                         FILE's folder/mission_logs)
  --quiet                no progress lines

examples:
  sonarloop mission config/mission_20.yaml         # the default model, one seed, re-looks
  sonarloop mission mission_20 --no-relook --seeds 5 --report out/m20.json --out out/m20
  sonarloop mission survey_rocky --no-relook --seeds 5 --layout random
  sonarloop mission config/soak_1km2.yaml --no-relook --match-radius 6   # 3 h 40 min, drifting
  sonarloop train --surveys survey_clutter,mission_20 --out out/mine.slpca
  sonarloop mission config/mission_20.yaml --model out/mine.slpca
  sonarloop mission config/mission_20.yaml --realtime --rate 5
)",
    run_mission, 19};
SONARLOOP_REGISTER_COMMAND(kMissionCommand);

}  // namespace sonarloop::tools
