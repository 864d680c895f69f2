// sonarloop autonomy: the example autonomy agent (autonomy/agent.h) in the loop — contacts from the
// onboard consumer over UDP, navigation from CAN, its pose to the emulator over UDP.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "autonomy/agent.h"
#include "autonomy/autonomy_io.h"
#include "autonomy/survey.h"
#include "mission/agent_setup.h"
#include "tools/args.h"
#include "tools/cli_helpers.h"
#include "tools/commands.h"
#include "tools/output_file.h"
#include "tools/scenario_source.h"

namespace sonarloop::tools {
using autonomy::agent_report_json;
using autonomy::AgentRunInfo;
using autonomy::ContactListener;
using autonomy::NavFix;
using autonomy::NavListener;
using autonomy::PosePublisher;
namespace {

using Clock = std::chrono::steady_clock;

// How long to wait for the emulator's socketcand server (it opens after building the scene).
constexpr double kConnectTimeoutS = 120.0;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::int64_t unix_now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

net::HostPort udp_option(const Args& args, const std::string& name) {
  const auto v = args.get(name);
  if (!v) throw UsageError(name + " udp:HOST:PORT is required");
  if (v->rfind("udp:", 0) != 0)
    throw UsageError(name + ": expected udp:HOST:PORT, got '" + *v + "'");
  try {
    return net::parse_host_port(v->substr(4));
  } catch (const std::invalid_argument& e) {
    throw UsageError(name + ": " + e.what());
  }
}

// The area, origin, speed and altitude of the scenario (or the options that replace them).
mission::AgentSetup setup_from(const Args& args, double spacing_m) {
  const config::Scenario sc = load_scenario_or_default(args.get("--scenario"));
  mission::AgentOverrides o = agent_options(args);
  o.line_spacing_m = spacing_m;
  o.speed_m_s = args.get_double("--speed", 0.1, 20.0);
  o.altitude_m = args.get_double("--altitude", 1.0, 100.0);
  try {
    return mission::make_agent_setup(sc, o);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--area-margin: ") + e.what());
  }
}

void print_events(autonomy::Agent& agent, bool quiet) {
  for (const std::string& e : agent.take_events()) {
    if (!quiet) std::fprintf(stderr, "autonomy: t=%.1f s: %s\n", agent.state().t_s, e.c_str());
  }
}

// The survey and the wiring, one line each.
void print_plan(const mission::AgentSetup& setup, const std::vector<autonomy::Leg>& survey,
                double spacing_m, const AgentRunInfo& info, double rate,
                const ContactListener& contacts, const net::HostPort& pose_to,
                const std::string& nav_spec) {
  std::fprintf(stderr,
               "autonomy: survey of (%.0f, %.0f)-(%.0f, %.0f) m, %zu lines %.0f m apart (%.0f "
               "m), re-looks %s (margin threshold %.3g, pass range %.0f m), rate %g\n",
               setup.area.min.north_m, setup.area.min.east_m, setup.area.max.north_m,
               setup.area.max.east_m, survey.size(), spacing_m, info.survey_plan_m,
               info.relooks ? "on" : "off", info.threshold, setup.params.relook.pass_range_m, rate);
  std::fprintf(stderr, "autonomy: contacts on %s, pose to udp %s, nav from %s ...\n",
               contacts.describe().c_str(), net::to_string(pose_to).c_str(), nav_spec.c_str());
}

// How the agent flies: at `rate` times real time, publishing its pose at pose_hz, until the
// survey is done and drain_s of mission time has passed, max_duration_s, or a stop request.
struct Flight {
  double rate = 1.0;
  double pose_hz = 20.0;
  double drain_s = 20.0;
  double max_duration_s = 1e7;
  bool quiet = false;
};

// The agent's loop: steps the vehicle model to the mission time, hands it the contacts received,
// publishes its pose, and measures how far the navigation is from it (into info).
void fly(autonomy::Agent& agent, const Flight& f, NavListener& nav, ContactListener& contacts,
         PosePublisher& pose, AgentRunInfo& info) {
  const auto wall0 = Clock::now();
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / f.pose_hz));
  auto next = wall0;
  double offset_sum = 0.0;
  std::uint64_t offset_n = 0, last_position_updates = 0;
  double done_at_s = -1.0;  // mission time the survey ended, < 0 while flying
  while (!stop_requested()) {
    next += period;
    std::this_thread::sleep_until(next);
    // the model runs at the emulator's rate: mission time = rate x wall time
    const double target_s = f.rate * seconds_since(wall0);
    const NavFix fix = nav.latest();
    agent.step(target_s - agent.state().t_s, fix.seabed_depth_m);
    for (const atr::Contact& c : contacts.take())
      agent.on_contact(c);
    pose.publish(agent.state(), unix_now_ns());
    if (fix.position && fix.position_updates != last_position_updates) {
      last_position_updates = fix.position_updates;
      const double off = autonomy::distance_m(*fix.position, agent.state().position);
      offset_sum += off;
      ++offset_n;
      info.nav_offset_max_m = std::max(info.nav_offset_max_m, off);
    }
    print_events(agent, f.quiet);
    // done: wait `drain_s` of mission time for the last contacts (which may ask for re-looks)
    if (agent.mission_done()) {
      if (done_at_s < 0) {
        done_at_s = agent.state().t_s;
        if (!f.quiet)
          std::fprintf(stderr, "autonomy: survey done, waiting %.0f s for contacts\n", f.drain_s);
      }
      if (agent.state().t_s - done_at_s >= f.drain_s) break;
    } else {
      done_at_s = -1.0;
    }
    if (agent.state().t_s >= f.max_duration_s) break;
  }
  info.wall_time_s = seconds_since(wall0);
  info.nav_offset_mean_m = offset_n ? offset_sum / static_cast<double>(offset_n) : 0.0;
}

// The mission's outcome, on one line.
void print_result(const autonomy::Agent& agent, const AgentRunInfo& info) {
  int confirmed = 0;
  for (const auto& o : agent.objects())
    confirmed += o.decision.state == autonomy::FinalState::kConfirmed;
  std::fprintf(stderr,
               "autonomy: %s after %.0f s of mission (%.1f s wall): %.0f m flown, %.0f m and "
               "%.0f s on %zu re-looks; %zu objects, %d confirmed; %llu contacts, %llu nav "
               "frames\n",
               info.stopped ? "stopped" : "done", agent.state().t_s, info.wall_time_s,
               agent.travelled_m(), agent.detour_distance_m(), agent.detour_time_s(),
               agent.relooks().size(), agent.objects().size(), confirmed,
               static_cast<unsigned long long>(info.contacts_received),
               static_cast<unsigned long long>(info.nav.frames));
}

int run_autonomy(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--scenario"},
                         {"--contacts"},
                         {"--nav"},
                         {"--pose-to"},
                         {"--rate"},
                         {"--threshold"},
                         {"--no-relook", false},
                         {"--relook-all", false},
                         {"--max-relooks"},
                         {"--relook-timing"},
                         {"--relook-budget"},
                         {"--pass-range"},
                         {"--line-spacing"},
                         {"--area"},
                         {"--area-margin"},
                         {"--altitude"},
                         {"--speed"},
                         {"--pose-hz"},
                         {"--drain"},
                         {"--max-duration"},
                         {"--report"},
                         {"--quiet", false}});
  if (!args.positionals().empty()) {
    throw UsageError("unexpected argument '" + args.positionals()[0] + "'");
  }
  const bool quiet = args.has("--quiet");
  const net::HostPort contacts_at = udp_option(args, "--contacts");
  const net::HostPort pose_to = udp_option(args, "--pose-to");
  const auto nav_spec = args.get("--nav");
  if (!nav_spec)
    throw UsageError("--nav socketcand:HOST:PORT (or a SocketCAN interface) is required");
  const double rate = args.get_double("--rate", 0.01, 1000.0).value_or(1.0);
  const double pose_hz = args.get_double("--pose-hz", 1.0, 1000.0).value_or(20.0);
  const double drain_s = args.get_double("--drain", 0.0, 3600.0).value_or(20.0);
  const double max_duration_s = args.get_double("--max-duration", 1.0, 1e7).value_or(1e7);
  const double spacing_m = args.get_double("--line-spacing", 1.0, 1e4).value_or(40.0);
  std::optional<OutputFile> report;
  if (const auto r = args.get("--report")) report.emplace("--report", *r);

  const mission::AgentSetup setup = setup_from(args, spacing_m);
  const std::vector<autonomy::Leg>& survey = setup.survey;
  autonomy::Agent agent(setup.params, survey, setup.start);
  const LocalTangentPlane ltp(setup.origin);
  AgentRunInfo info;
  info.rate = rate;
  info.threshold = setup.params.margin_threshold;
  info.relooks = setup.params.relooks;
  info.survey_plan_m = autonomy::plan_length_m(survey);

  install_stop_flag();
  ContactListener contacts(contacts_at);
  PosePublisher pose(pose_to, ltp);
  if (!quiet) {
    print_plan(setup, survey, spacing_m, info, rate, contacts, pose_to, *nav_spec);
  }
  // the pose first (the emulator waits for it), then the bus (its server may still be starting)
  pose.publish(agent.state(), unix_now_ns());
  NavListener nav(*nav_spec, ltp, kConnectTimeoutS);
  if (!quiet) std::fprintf(stderr, "autonomy: nav connected (%s)\n", nav.describe().c_str());

  Flight flight;
  flight.rate = rate;
  flight.pose_hz = pose_hz;
  flight.drain_s = drain_s;
  flight.max_duration_s = max_duration_s;
  flight.quiet = quiet;
  fly(agent, flight, nav, contacts, pose, info);
  info.stopped = stop_requested();
  info.contacts_received = contacts.received();
  info.contacts_malformed = contacts.malformed();
  info.contacts_dropped = contacts.dropped();
  info.poses_sent = pose.sent();
  info.nav = nav.latest();
  print_result(agent, info);
  if (report) report->write_and_close(agent_report_json(agent, info) + "\n");
  return 0;
}

}  // namespace

const Command kAutonomyCommand{
    "autonomy", "the example autonomy agent: survey, re-look uncertain contacts, decide",
    R"(usage: sonarloop autonomy --contacts udp:HOST:PORT --nav SPEC --pose-to udp:HOST:PORT [options]

An example vehicle brain in the loop with the emulator (docs/autonomy.md). It flies a lawnmower
survey with a simple vehicle model (speed, bounded turn rate, altitude keeping) and publishes
its pose to the emulator (`run --pose-from udp:...`, drivers/pose/pose_message.md) so that the
pings come from where it steers. It reads the onboard consumer's contacts (`onboard --contacts
udp:...`: one JSON line per datagram, atr/contact.h) and the navigation from CAN (NMEA 2000;
the seabed's depth from PGN 128267 closes the altitude keeping). An object whose decision
margin (runner-up distance - distance, over the distance; or 1 - the open-set score) is below
--threshold, or whose target probability (a model with contact gates) is below 0.5, is
uncertain and gets a re-look: a straight pass about 90 degrees from the first look, the contact
abeam at --pass-range; by default once the survey is done, the cheapest first, within the
re-look budget (--relook-timing immediate: at once, the survey resumed where it was cut). Looks of an
object are fused (the onboard's fused fields, or a sum of normalised distances) and every object
ends confirmed (class, mine / non-mine, looks) or uncertain. The model runs at --rate times real
time, as the emulator must. Ends when the survey is done and --drain seconds passed, or on
Ctrl-C (the report is still written).

options:
  --contacts udp:HOST:PORT  listen for the contacts there (port 0: any free port)
  --nav SPEC             socketcand:HOST:PORT[:CHANNEL] (the emulator's `--can socketcand:`
                         server; retried for 120 s while it starts) or a SocketCAN interface
  --pose-to udp:HOST:PORT  where the emulator listens (`run --pose-from udp:HOST:PORT`)
  --scenario FILE        the scenario flown (default: the embedded default): its origin, its
                         seabed's extent (the survey area, less --area-margin), the vehicle's
                         speed, turn rate, climb rate and altitude
  --area N0,E0,N1,E1     survey this rectangle instead (metres, scenario frame)
  --area-margin M        inset of the seabed's extent for the survey area (default 50)
  --line-spacing M       lawnmower line spacing (default 40: for the 50 m strip sonar, the
                         range less the nadir gap)
  --threshold T          decision margin below which a contact is re-looked (default 0.05)
  --no-relook            survey only: objects keep their first decision
  --relook-all           re-look every uncertain object; by default one that is non-mine
                         either way (its mine margin reaches --threshold, e.g. a rock unsure
                         between the two hemispheres) is not re-looked
  --relook-timing T      after-survey (default: the survey to its end, then the objects still
                         uncertain, the cheapest to reach first) or immediate (each as it
                         comes: the survey is cut and resumed after it)
  --relook-budget F      after the survey, the re-looks take at most F times the survey's
                         planned time (default 0.5); none: no limit
  --max-relooks N        the mission's re-look budget: the first N uncertain objects only
  --pass-range M         ground range of the contact on the re-look pass (default 25)
  --altitude M           altitude kept above the seabed (default: the scenario's)
  --speed M_S            vehicle speed (default: the scenario's)
  --rate X               the emulator's --rate factor (default 1)
  --pose-hz F            pose messages per wall second (default 20)
  --drain S              mission seconds to wait for contacts after the survey (default 20)
  --max-duration S       stop after S mission seconds
  --report FILE          the JSON report: objects, re-looks (geometry, latency), distances
  --quiet                no progress lines (the summary still prints)

examples:
  sonarloop onboard --listen 127.0.0.1:5600 --model out/atr.slpca --scenario config/mission_20.yaml \
      --contacts udp:127.0.0.1:5610 &
  sonarloop run config/mission_20.yaml --udp 127.0.0.1:5600 --can socketcand:127.0.0.1:29536 \
      --pose-from udp:127.0.0.1:5700 --rate 5 &
  sonarloop autonomy --scenario config/mission_20.yaml --contacts udp:127.0.0.1:5610 \
      --nav socketcand:127.0.0.1:29536 --pose-to udp:127.0.0.1:5700 --rate 5 --report out/agent.json
  (or all three at once: sonarloop mission config/mission_20.yaml --model out/atr.slpca)
)",
    run_autonomy, 18};
SONARLOOP_REGISTER_COMMAND(kAutonomyCommand);

}  // namespace sonarloop::tools
