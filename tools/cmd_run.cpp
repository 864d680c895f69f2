// sonarloop run: the real-time emulator (emulator/emulator.h) — pings as XTF over UDP, navigation
// as NMEA 2000 on CAN, recordings, live statistics.
#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "atr/contact.h"
#include "atr/imc_contacts.h"
#include "atr/in_process_onboard.h"
#include "atr/onboard_report.h"
#include "drivers/xtf/xtf_codec.h"
#include "emulator/emulator.h"
#include "emulator/mcap_device.h"
#include "emulator/pacer.h"
#include "emulator/realtime_priority.h"
#include "emulator/run_report.h"
#include "emulator/run_stats.h"
#include "mission/onboard_device.h"
#include "tools/args.h"
#include "tools/chip_options.h"
#include "tools/cli_helpers.h"
#include "tools/commands.h"
#include "tools/output_file.h"
#include "tools/scenario_source.h"
#include "tools/web_option.h"
#include "web/emulator_device.h"
#include "web/web_view.h"

namespace sonarloop::tools {
using atr::InProcessOnboard;
using atr::print_onboard_stats;
using mission::OnboardDevice;
using web::kWebStatsEveryS;
using web::open_web_view;
using web::print_web_summary;
using web::web_stats_of;
using web::WebView;
using web::WebViewDevice;
namespace {

// A stop request (SIGINT/SIGTERM) during start-up: nothing was sent or recorded.
int report_startup_stop(const emulator::StartupStopped& e) {
  const int sig = stop_signal();
  std::fprintf(stderr, "sonarloop run: %s by %s\n", e.what(),
               sig == SIGTERM  ? "SIGTERM"
               : sig == SIGINT ? "SIGINT"
                               : "a stop request");
  return 0;
}

// The emulator's options from the command line (all but the statistics interval); a bad value is
// a UsageError naming the option.
emulator::EmulatorOptions emulator_options(const Args& args) {
  emulator::EmulatorOptions o;
  o.duration_s = args.get_double("--duration", 1e-3, 1e9);
  if (const auto udp = args.get("--udp")) {
    try {
      o.udp = net::parse_host_port(*udp);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--udp: ") + e.what());
    }
    if (o.udp->port == 0) throw UsageError("--udp " + *udp + ": the port must not be 0");
  }
  if (const auto imc = imc_option(args)) {
    emulator::ImcDeviceOptions io;
    io.destination = *imc;
    io.system = imc_system_option(args);
    io.system_name = args.get_or("--imc-name", "sonarloop");
    o.imc = io;
  } else if (args.has("--imc-system") || args.has("--imc-name")) {
    throw UsageError("--imc-system and --imc-name apply to --imc only");
  }
  o.can_specs = args.get_all("--can");
  o.record_dir = args.get("--record");
  // the MCAP recording: --mcap FILE, else DIR/run.mcap with --record; `--mcap none`: none
  if (const auto mcap = args.get("--mcap")) {
    if (*mcap != "none") o.mcap_path = *mcap;
  } else if (o.record_dir) {
    o.mcap_path = *o.record_dir + "/run.mcap";
  }
  try {
    o.rate = emulator::parse_rate(args.get_or("--rate", "realtime"));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  o.threads = static_cast<int>(args.get_int("--threads", 1, 256)
                                   .value_or(std::max(1u, std::thread::hardware_concurrency())));
  o.pose_from = args.get("--pose-from");
  // where the emulated vehicle listens, for an IMC console (Announce's services)
  if (o.imc && o.pose_from && o.pose_from->rfind("imc:udp:", 0) == 0)
    o.imc->services = "imc+udp://" + o.pose_from->substr(8) + "/";
  o.renderer = renderer_option(args);
  if (const auto mb = args.get_double("--memory-budget", 16.0, 1e6)) {
    o.seabed_cache_bytes = static_cast<std::size_t>(*mb * 1048576.0);
  }
  o.stale_after_s = args.get_double("--stale-after", 1e-3, 3600.0).value_or(2.0);
  o.pose_delay_s = args.get_double("--pose-delay", 0.0, 3600.0).value_or(o.pose_delay_s);
  if ((args.has("--stale-after") || args.has("--pose-delay")) && !o.pose_from) {
    throw UsageError("--stale-after and --pose-delay apply to --pose-from only");
  }
  if (o.pose_from && o.rate.max) {
    throw UsageError("--pose-from needs --rate realtime or a factor, not max");
  }
  if (const auto e = args.get_double("--epoch", 0.0, 253402300799.0)) {
    o.epoch_utc_ns = static_cast<std::int64_t>(std::llround(*e * 1e9));
  }
  if (const auto ms = args.get_double("--lateness-tolerance-ms", 1e-3, 1e4)) {
    o.deadline_tolerance_s = *ms * 1e-3;
  }
  o.realtime_priority =
      static_cast<int>(args.get_int("--realtime-priority", emulator::kMinRealtimePriority,
                                    emulator::kMaxRealtimePriority)
                           .value_or(0));
  return o;
}

// Statistics go to the console every print_every s (0: never) and to the --web page every
// kWebStatsEveryS: the emulator reports at the shorter interval.
double stats_interval_s(double print_every, const std::optional<net::HostPort>& web_address) {
  if (!web_address) return print_every;
  return print_every > 0 ? std::min(print_every, kWebStatsEveryS) : kWebStatsEveryS;
}

// The onboard consumer fed from the run's pings (--classify): contacts in the scenario's frame,
// to --contacts, the --web page, the MCAP recording (/contacts) and, with --imc, as IMC map
// features (atr/imc_contacts.h).
std::unique_ptr<InProcessOnboard> make_onboard(atr::Model model, const config::Scenario& scenario,
                                               const Args& args, const emulator::Emulator& emu,
                                               const emulator::EmulatorOptions& o,
                                               const std::vector<std::uint8_t>& file_header,
                                               std::unique_ptr<WebView>& web) {
  atr::OnboardOptions onboard_options;  // contacts in the scenario's frame
  onboard_options.frame_origin =
      GeoPoint{scenario.scene.origin.latitude_deg, scenario.scene.origin.longitude_deg};
  std::shared_ptr<atr::ImcContactSender> imc;
  if (o.imc) imc = std::make_shared<atr::ImcContactSender>(o.imc->destination, o.imc->system);
  emulator::McapDevice* mcap = emu.find_device<emulator::McapDevice>();
  if (mcap) mcap->record_contacts();
  InProcessOnboard::ContactObserver observer;
  if (web || imc || mcap) {
    // on the consumer's thread (the sender is used there only), or in finish()
    observer = [&web, imc, mcap](const atr::Contact& c) {
      if (web) web->hub.push_contact(c);
      if (imc) imc->send(c);
      if (mcap) mcap->add_contact({c.time_utc_ns, c.id, c.north_m, c.east_m, atr::contact_json(c)});
    };
  }
  return std::make_unique<InProcessOnboard>(std::move(model), onboard_options,
                                            args.get("--contacts"), file_header, emu.packet_bytes(),
                                            o.rate.max, std::move(observer));
}

// After the run: the statistics, the onboard consumer's, the web page's, a recording error and
// --stats-json. Returns the exit status (1 when the recording failed).
int finish_run(const emulator::RunStats& stats, InProcessOnboard* onboard, WebView* web,
               std::optional<OutputFile>& stats_json_file) {
  const int sig = stop_signal();
  print_run_summary(stats, sig == SIGINT    ? "stopped by SIGINT"
                           : sig == SIGTERM ? "stopped by SIGTERM"
                                            : "done");
  if (onboard) print_onboard_stats("onboard", onboard->finish(), &onboard->queue());
  if (web) {
    web->hub.push_stats(web_stats_of(stats));
    web->hub.close();  // the last lines and statistics go out; then the counts are final
    print_web_summary(*web);
  }
  // after the statistics, so that a full disk never hides them
  if (!stats.mcap_error.empty()) {
    std::fprintf(stderr, "sonarloop run: error: MCAP recording: %s\n", stats.mcap_error.c_str());
  }
  if (!stats.recording_error.empty()) {
    std::fprintf(stderr, "sonarloop run: error: --record: %s\n", stats.recording_error.c_str());
  }
  if (stats_json_file) stats_json_file->write_and_close(emulator::stats_json(stats) + "\n");
  return stats.recording_error.empty() && stats.mcap_error.empty() ? 0 : 1;
}

int run_run(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--duration"},
                         {"--udp"},
                         {"--imc"},
                         {"--imc-system"},
                         {"--imc-name"},
                         {"--can", true, true},
                         {"--record"},
                         {"--mcap"},
                         {"--rate"},
                         {"--threads"},
                         {"--quiet", false},
                         {"--stats-json"},
                         {"--stats-every"},
                         {"--pose-from"},
                         {"--stale-after"},
                         {"--pose-delay"},
                         {"--epoch"},
                         {"--classify"},
                         {"--contacts"},
                         {"--gate-threshold"},
                         {"--renderer"},
                         {"--memory-budget"},
                         {"--web"},
                         {"--lateness-tolerance-ms"},
                         {"--realtime-priority"}});
  if (args.positionals().size() > 1) throw UsageError("expected at most one SCENARIO.yaml");
  const bool quiet = args.has("--quiet");

  emulator::EmulatorOptions o = emulator_options(args);
  // validated with --quiet too (which silences the lines)
  const double stats_every = args.get_double("--stats-every", 0.0, 3600.0).value_or(5.0);
  const double print_every = quiet ? 0.0 : stats_every;
  const std::optional<net::HostPort> web_address = web_option(args);
  // the page gets statistics every second; the console keeps its own interval
  o.stats_interval_s = stats_interval_s(print_every, web_address);
  const auto stats_json = args.get("--stats-json");
  // opened now: an unwritable place fails before the run, not after it
  std::optional<OutputFile> stats_json_file;
  if (stats_json) stats_json_file.emplace("--stats-json", *stats_json);
  const auto classify = args.get("--classify");
  if (args.has("--contacts") && !classify) throw UsageError("--contacts needs --classify MODEL");
  if (args.has("--gate-threshold") && !classify) {
    throw UsageError("--gate-threshold needs --classify MODEL");
  }
  // the model first: a bad file fails before the scene is built
  std::optional<atr::Model> model = load_model_if(classify);
  set_gate_threshold(model, args.get_double("--gate-threshold", 0.0, 1.0));

  config::Scenario scenario = load_scenario_or_default(
      args.positionals().empty() ? std::nullopt : std::optional(args.positionals()[0]));

  emulator::MonotonicClock clock;
  emulator::EmulatorHooks hooks;
  hooks.message = [quiet](std::string_view text) {
    const bool warning = text.rfind("warning", 0) == 0;
    if (quiet && !warning) return;
    std::fprintf(stderr, "%.*s\n", static_cast<int>(text.size()), text.data());
  };
  // before the scene is built: a port in use fails at once
  std::unique_ptr<WebView> web = open_web_view(
      web_address,
      GeoPoint{scenario.scene.origin.latitude_deg, scenario.scene.origin.longitude_deg},
      "sonarloop run");
  double next_print_s = print_every;
  hooks.on_stats = [&next_print_s, print_every](const emulator::RunStats& s) {
    // with --web this is called every kWebStatsEveryS: print at the console's own interval
    constexpr double kSlackS = 1e-3;
    if (print_every <= 0 || s.wall_time_s + kSlackS < next_print_s) return;
    while (next_print_s <= s.wall_time_s + kSlackS)
      next_print_s += print_every;
    char line[512];
    emulator::format_stats_line(s, line, sizeof line);
    std::fprintf(stderr, "%s\n", line);
  };
  hooks.stop_requested = [] { return stop_requested(); };
  std::unique_ptr<InProcessOnboard> onboard;  // --classify: fed by its device

  if (!quiet) {
    std::fprintf(stderr, "sonarloop run: scenario '%s' (seed %llu), preparing the scene ...\n",
                 scenario.scene.name.c_str(), static_cast<unsigned long long>(scenario.scene.seed));
  }
  // before the start-up work: Ctrl-C or SIGTERM during a long start-up stops it cleanly (the
  // emulator polls the flag); a second one ends the process at once
  install_stop_flag();
  std::optional<emulator::Emulator> emu_holder;
  try {
    emu_holder.emplace(scenario, o, clock, hooks);
  } catch (const emulator::StartupStopped& e) {
    return report_startup_stop(e);
  }
  emulator::Emulator& emu = *emu_holder;
  const std::vector<std::uint8_t> file_header = xtf::encode_file_header(emu.file_header());
  if (web) web->hub.push_datagram(file_header);
  if (model) {
    onboard = make_onboard(std::move(*model), scenario, args, emu, o, file_header, web);
    emu.add_device(std::make_unique<OnboardDevice>(*onboard));
    if (!quiet) {
      std::fprintf(stderr, "onboard: classifying with %s, contacts to %s\n", classify->c_str(),
                   onboard->contacts_destination().c_str());
    }
  }
  if (web)
    emu.add_device(std::make_unique<WebViewDevice>(web->hub));  // after the consumer, as before
  if (!quiet) print_run_setup(emu, o);
  emulator::RunStats stats;
  try {
    stats = emu.run();
  } catch (const emulator::StartupStopped& e) {
    return report_startup_stop(e);
  }
  return finish_run(stats, onboard.get(), web.get(), stats_json_file);
}

}  // namespace

const Command kRunCommand{
    "run", "the real-time emulator: pings as XTF over UDP, navigation as NMEA 2000 on CAN",
    R"(usage: sonarloop run [SCENARIO.yaml] [options]

Flies the scenario's vehicle along its trajectory in real time, renders each ping at the
sonar's ping period and streams it as one XTF packet per UDP datagram (the 1024-byte XTF file
header first and every 2 s of simulation), and publishes the navigation as NMEA 2000 frames
(PGNs 129025 129026 127250 127251 127257 128259 128267 126992 at their standard rates) on CAN.
Ping k is rendered from the pose at k x ping period and sent one receive window (2 x range /
sound speed) later, as a real sidescan would. Live statistics every 5 s and at exit on stderr.
Without SCENARIO.yaml the embedded default scenario is used (see config/default.yaml).

options:
  --duration S           simulated seconds to run (default: the trajectory's duration;
                         with --pose-from: until stopped)
  --udp HOST:PORT        stream the pings there (default: no stream)
  --imc udp:HOST:PORT    also speak IMC there (DUNE / Neptus; docs/formats.md §7): SonarData
                         per ping, EstimatedState at 10 Hz, Heartbeat and Announce, unicast
                         (Neptus listens on port 6001 by default); with --classify the
                         contacts too, as map features (as `onboard --imc`)
  --imc-system ID        the emulated vehicle's IMC address (default 0x2050)
  --imc-name NAME        its IMC system name, as a console lists it (default sonarloop)
  --can SPEC             publish navigation on SPEC; repeat for several: vcan0 (SocketCAN),
                         socketcand:HOST:PORT (a socketcand server for python-can & co),
                         log:FILE (candump log), none
  --record DIR           write DIR/pings.xtf, DIR/nav.log (candump) and DIR/truth.csv,
                         each a whole packet / line per write (whole after any crash); on
                         a write error (a full disk) the recording stops, the run goes on,
                         and run exits with status 1 after the statistics; and DIR/run.mcap
                         for ROS 2 tools (ros2 bag, Foxglove: docs/formats.md §8), with
                         --classify the contacts too (/contacts, written at the end)
  --mcap FILE            write the MCAP recording there instead (without --record: that file
                         alone); `--mcap none`: no MCAP file
  --rate R               realtime (default), max (as fast as possible, nothing dropped,
                         reproducible), or a factor X of real time (0.01..1000)
  --threads N            render threads (default: all cores)
  --memory-budget MB     what the seabed's tile caches may hold (default 192, at least 16):
                         most of run's memory (the rest: about 70 MB on the default
                         scenario, 170 MB on the 1 km2 survey of config/soak_1km2.yaml).
                         Tiles beyond it are evicted and made again when the vehicle
                         comes back; the summary gives the caches' hit rates
  --quiet                no start-up lines or live statistics (warnings and the final
                         summary are still printed)
  --stats-every S        live statistics interval in wall seconds (default 5; 0 = none)
  --stats-json FILE      write the final statistics as JSON (FILE is opened at start:
                         an unwritable place fails before the run)
  --pose-from SPEC       follow an external vehicle: can:IFACE, socketcand:HOST:PORT[:CHANNEL]
                         or udp:HOST:PORT (drivers/pose/pose_message.md); pings pause while the
                         pose is stale. Each ping is rendered at the pose of its own time
                         less --pose-delay, interpolated between the pose samples (UDP: at
                         their time stamps), extrapolated when none is newer (counted)
  --pose-delay S         that delay: the lag of the rendered pose behind the vehicle
                         (default 0.1 s, one update at 10 Hz; 0: no lag, every ping
                         extrapolated from the last two samples)
  --stale-after S        age beyond which the external pose is stale (default 2 s)
  --epoch UNIX_S         UTC of the mission start, seconds since 1970 (default: now; with
                         --rate max 1767225600 = 2026-01-01T00:00:00Z, for reproducible files)
  --classify MODEL       run the onboard consumer in-process on the pings (as `sonarloop
                         onboard` does on the UDP stream): detect, classify with MODEL (of
                         `sonarloop train`; `default`: the default model of `sonarloop
                         mission`), one JSON contact report per object
  --contacts FILE        write the contact reports there (default stderr); udp:HOST:PORT:
                         one JSON line per UDP datagram there (`sonarloop autonomy`)
  --gate-threshold P     with --classify: the classification gate's operating point (0 to 1;
                         default: the model's; see `sonarloop onboard --help`)
  --renderer R           profile (default: the heightfield profile renderer) or raytrace (the
                         Embree reference; it builds views of the seabed as the vehicle goes,
                         so a real-time run may drop pings while it does: docs/rendering.md)
  --realtime-priority N  run the publisher (the thread that sends each ping and frame at its
                         deadline) at SCHED_FIFO priority N (1..99) and lock the memory,
                         where permitted (root, CAP_SYS_NICE, `ulimit -r`/`-l`); where not,
                         a message says why and the run goes on at normal priority. The
                         render threads keep normal priority. For shared machines
  --lateness-tolerance-ms MS
                         a ping sent more than MS after its send time counts as a
                         deadline miss (default 1; 0.001..10000)
  --web HOST:PORT        serve the live operator view there (docs/web.md): waterfall, track
                         and contacts (with --classify), statistics, pause; PORT alone binds
                         127.0.0.1, port 0 a free port (the URL is printed). Read-only; a
                         slow browser loses lines, never delays a ping

examples:
  sonarloop run --duration 30 --udp 127.0.0.1:5600
  sonarloop run --udp 127.0.0.1:5600 --can socketcand:127.0.0.1:29536 --record out/run
  sonarloop run config/default.yaml --rate max --record out/max --stats-json out/max.json
  sonarloop run --can vcan0 --can log:nav.log --rate 2
  sonarloop run --pose-from udp:127.0.0.1:5700 --udp 127.0.0.1:5600 --stale-after 1
  sonarloop run --udp 127.0.0.1:5600 --realtime-priority 50 --lateness-tolerance-ms 2
  sonarloop run --rate max --classify out/atr.slpca --contacts out/contacts.jsonl
  sonarloop run --udp 127.0.0.1:5600 --web 8080     (then open http://127.0.0.1:8080/)
  sonarloop run --imc udp:127.0.0.1:6001 --imc-name auv-sim     (a Neptus console on this host)
  sonarloop run --rate max --duration 60 --mcap out/run.mcap      (then: foxglove-studio, ros2 bag)
  sonarloop run --classify out/atr.slpca --web 127.0.0.1:0
)",
    run_run, 10};
SONARLOOP_REGISTER_COMMAND(kRunCommand);

}  // namespace sonarloop::tools
