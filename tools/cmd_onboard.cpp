// sonarloop onboard: the onboard consumer (atr/onboard_pipeline.h) — receives the emulator's
// sonar stream (UDP, or an .xtf file), detects objects, classifies them with a trained PCA model
// and writes a contact report per object.
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "atr/contact_writer.h"
#include "atr/imc_contacts.h"
#include "atr/onboard_pipeline.h"
#include "atr/onboard_report.h"
#include "atr/packet_queue.h"
#include "drivers/net/udp_receiver.h"
#include "drivers/xtf/xtf_file.h"
#include "tools/args.h"
#include "tools/chip_options.h"
#include "tools/cli_helpers.h"
#include "tools/commands.h"
#include "tools/output_file.h"
#include "tools/scenario_source.h"
#include "tools/web_option.h"
#include "web/web_view.h"

namespace sonarloop::tools {
using atr::ContactWriter;
using atr::onboard_stats_json;
using atr::print_onboard_stats;
using web::CpuMeter;
using web::kWebStatsEveryS;
using web::open_web_view;
using web::print_web_summary;
using web::web_stats_of;
using web::WebView;
namespace {

// Largest UDP payload (IPv4).
constexpr std::size_t kMaxDatagramBytes = 65536;
// Datagrams queued between the socket thread and the pipeline: 2048 x 64 KiB of address space,
// of which only the pages used are touched (4.5 KB per default ping: 9 MB, 2 s at --rate 10).
constexpr std::size_t kQueueSlots = 2048;
// Receive buffer asked of the kernel (capped at net.core.rmem_max).
constexpr int kReceiveBufferBytes = 8 << 20;
// The socket thread's receive timeout: bounds how long a stop request waits.
constexpr int kPollMs = 50;
// A quiet stream this long hands over the pings waiting in the reorder buffer.
constexpr double kFlushAfterS = 0.5;

double seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

// Where each datagram goes: the pipeline, and the web view (--web) with the statistics every
// kWebStatsEveryS.
struct Consumer {
  atr::OnboardPipeline& pipeline;
  WebView* web = nullptr;
  bool web_lossless = false;  // --xtf: wait for the view rather than drop (no deadline to keep)
  CpuMeter cpu;
  std::chrono::steady_clock::time_point next_stats{};

  void feed(std::span<const std::uint8_t> datagram) {
    pipeline.feed(datagram);
    if (web) web->hub.push_datagram(datagram, web_lossless);
  }
  void flush() { pipeline.flush(); }
  // the statistics to the page, at most every kWebStatsEveryS (always when `now_or_never`)
  void tick(bool now_or_never = false) {
    if (!web) return;
    const auto now = std::chrono::steady_clock::now();
    if (!now_or_never && now < next_stats) return;
    next_stats = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(kWebStatsEveryS));
    web->hub.push_stats(web_stats_of(pipeline.stats(), cpu.percent()));
  }
};

// Reads an XTF file as the stream it was recorded from: its file header, then every packet.
void feed_file(const std::string& path, Consumer& consumer, bool quiet) {
  xtf::XtfReader reader(path);
  consumer.feed(reader.file_header_bytes());
  xtf::XtfRawPacket packet;
  try {
    while (!stop_requested() && reader.next_raw(packet)) {
      consumer.feed(packet.bytes);
      consumer.tick();
    }
  } catch (const xtf::XtfFormatError& e) {
    // what was read is still processed
    std::fprintf(stderr, "sonarloop onboard: warning: %s; stopping there\n", e.what());
  }
  if (!quiet) {
    std::fprintf(stderr, "sonarloop onboard: read %llu packets from %s\n",
                 static_cast<unsigned long long>(reader.stats().packets), path.c_str());
  }
}

// The origin of the contacts' north_m / east_m: --origin LAT,LON, --origin first-ping, or the
// origin of --scenario FILE (default: the embedded default scenario, as `run` flies).
std::optional<GeoPoint> frame_origin(const Args& args) {
  const auto origin = args.get("--origin");
  if (origin && args.has("--scenario")) throw UsageError("give --origin or --scenario, not both");
  if (origin) {
    if (*origin == "first-ping") return std::nullopt;
    const auto comma = origin->find(',');
    char* end_lat = nullptr;
    char* end_lon = nullptr;
    const std::string lat_text = origin->substr(0, comma);
    const std::string lon_text = comma == std::string::npos ? "" : origin->substr(comma + 1);
    const double lat = std::strtod(lat_text.c_str(), &end_lat);
    const double lon = std::strtod(lon_text.c_str(), &end_lon);
    const bool ok = comma != std::string::npos && !lat_text.empty() && !lon_text.empty() &&
                    *end_lat == '\0' && *end_lon == '\0' && std::isfinite(lat) &&
                    std::isfinite(lon) && std::fabs(lat) <= kMaxOriginLatitudeDeg &&
                    std::fabs(lon) <= 180.0;
    if (!ok) {
      throw UsageError("--origin: expected LAT,LON in degrees (|LAT| <= " +
                       std::to_string(static_cast<int>(kMaxOriginLatitudeDeg)) +
                       ", |LON| <= 180) or first-ping, got '" + *origin + "'");
    }
    return GeoPoint{lat, lon};
  }
  const scene::SceneDesc scene = load_scene_or_default(args.get("--scenario"));
  return GeoPoint{scene.origin.latitude_deg, scene.origin.longitude_deg};
}

struct ListenOptions {
  net::HostPort address;
  std::optional<double> duration_s;
  std::optional<double> idle_exit_s;
  bool quiet = false;
};

// Receives datagrams on a socket thread into a queue, and feeds the pipeline from it here.
void listen(const ListenOptions& o, Consumer& consumer, atr::PacketQueue& queue) {
  net::UdpReceiver rx(o.address, kReceiveBufferBytes);
  std::fprintf(stderr, "sonarloop onboard: listening on %s (receive buffer %d bytes)\n",
               net::to_string(rx.bound_address()).c_str(), rx.receive_buffer_bytes());
  std::atomic<bool> done{false};
  std::string socket_error;
  std::thread reader([&] {
    std::vector<std::uint8_t> buf(kMaxDatagramBytes);
    try {
      while (!done.load() && !stop_requested()) {
        const auto d = rx.receive(buf, kPollMs);
        if (!d) continue;
        queue.push(std::span<const std::uint8_t>(buf.data(), d->size), false);
      }
    } catch (const std::exception& e) {
      socket_error = e.what();
    }
    queue.close();
  });

  using SteadyClock = std::chrono::steady_clock;
  const auto start = SteadyClock::now();
  auto last = start;
  bool got_any = false, flushed = true;
  for (;;) {
    const bool got = queue.pop([&](std::span<const std::uint8_t> p) { consumer.feed(p); }, kPollMs);
    consumer.tick();
    const auto now = SteadyClock::now();
    if (got) {
      last = now;
      got_any = true;
      flushed = false;
      continue;
    }
    if (queue.closed() && queue.size() == 0) break;  // socket thread ended (stop or error)
    if (!flushed && seconds(now - last) >= kFlushAfterS) {
      consumer.flush();
      flushed = true;
    }
    if (o.duration_s && seconds(now - start) >= *o.duration_s) break;
    if (o.idle_exit_s && got_any && seconds(now - last) >= *o.idle_exit_s) break;
    if (stop_requested()) break;
  }
  done.store(true);
  reader.join();
  // what the socket thread queued before it stopped
  while (queue.pop([&](std::span<const std::uint8_t> p) { consumer.feed(p); }, 0)) {
  }
  if (!socket_error.empty()) throw std::runtime_error(socket_error);
}

int run_onboard(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--listen"},
                         {"--xtf"},
                         {"--model"},
                         {"--contacts"},
                         {"--imc"},
                         {"--imc-system"},
                         {"--duration"},
                         {"--idle-exit"},
                         {"--reorder-window"},
                         {"--search-rows"},
                         {"--search-cols"},
                         {"--stats-json"},
                         {"--look-radius"},
                         {"--detector-threshold"},
                         {"--gate-threshold"},
                         {"--origin"},
                         {"--scenario"},
                         {"--quiet", false},
                         {"--web"}});
  if (!args.positionals().empty()) {
    throw UsageError("unexpected argument '" + args.positionals()[0] + "'");
  }
  const auto listen_at = args.get("--listen");
  const auto xtf_path = args.get("--xtf");
  if (listen_at.has_value() == xtf_path.has_value()) {
    throw UsageError("give exactly one input: --listen HOST:PORT or --xtf FILE.xtf");
  }
  const bool quiet = args.has("--quiet");
  ListenOptions lo;
  if (listen_at) {
    try {
      lo.address = net::parse_host_port(*listen_at);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--listen: ") + e.what());
    }
  } else if (args.has("--duration") || args.has("--idle-exit")) {
    throw UsageError("--duration and --idle-exit apply to --listen only");
  }
  lo.duration_s = args.get_double("--duration", 1e-3, 1e9);
  lo.idle_exit_s = args.get_double("--idle-exit", 1e-3, 1e9);
  lo.quiet = quiet;
  atr::OnboardOptions options;
  options.receiver.reorder_window = static_cast<int>(
      args.get_int("--reorder-window", 1, 4096).value_or(atr::kDefaultReorderWindow));
  options.search.rows =
      static_cast<int>(args.get_int("--search-rows", 0, 100).value_or(options.search.rows));
  options.search.cols =
      static_cast<int>(args.get_int("--search-cols", 0, 100).value_or(options.search.cols));
  options.look_radius_m =
      args.get_double("--look-radius", 0.0, 100.0).value_or(options.look_radius_m);
  if (const auto h = args.get_double("--detector-threshold", 0.0, 5.0)) {
    options.detector.min_height_m = *h;
    options.detector.candidate_min_height_m = std::min(options.detector.candidate_min_height_m, *h);
  }
  options.frame_origin = frame_origin(args);
  const auto stats_json = args.get("--stats-json");
  // opened now: an unwritable place fails before the run, not after it
  std::optional<OutputFile> stats_json_file;
  if (stats_json) stats_json_file.emplace("--stats-json", *stats_json);

  const std::optional<net::HostPort> web_address = web_option(args);

  std::optional<atr::Model> model = load_model_if(args.get("--model"));
  set_gate_threshold(model, args.get_double("--gate-threshold", 0.0, 1.0));
  // before listening: a port in use fails at once
  std::unique_ptr<WebView> web =
      open_web_view(web_address, options.frame_origin, "sonarloop onboard");
  if (!quiet) {
    if (model) {
      std::fprintf(stderr,
                   "sonarloop onboard: model %s: %zu classes, %d x %d chips (%g cm pixels), %d "
                   "aspect sector%s\n",
                   args.get("--model")->c_str(), model->classes.size(), model->chip_width,
                   model->chip_height, 100.0 * 3.0 / model->chip_width, model->aspect_sectors,
                   model->aspect_sectors == 1 ? "" : "s");
    } else {
      std::fprintf(stderr, "sonarloop onboard: no --model: objects are detected, not classified\n");
    }
  }
  ContactWriter contacts(args.get("--contacts"), stdout);
  std::optional<atr::ImcContactSender> imc;
  if (const auto to = imc_option(args)) {
    imc.emplace(*to, imc_system_option(args));
    if (!quiet)
      std::fprintf(stderr, "sonarloop onboard: contacts also as IMC map features to %s\n",
                   imc->describe().c_str());
  } else if (args.has("--imc-system")) {
    throw UsageError("--imc-system applies to --imc only");
  }
  atr::OnboardPipeline pipeline(std::move(model), options, [&](const atr::Contact& c) {
    contacts.write(c);
    if (imc) imc->send(c);
    if (web) web->hub.push_contact(c);
  });
  Consumer consumer{pipeline, web.get(), xtf_path.has_value(), CpuMeter{}, {}};
  install_stop_flag();
  std::optional<atr::PacketQueue> queue;
  if (xtf_path) {
    feed_file(*xtf_path, consumer, quiet);
  } else {
    queue.emplace(kQueueSlots, kMaxDatagramBytes);
    listen(lo, consumer, *queue);
  }
  pipeline.finish();
  consumer.tick(true);
  const atr::OnboardStats s = pipeline.stats();
  print_onboard_stats(
      stop_requested() ? "sonarloop onboard: stopped (SIGINT/SIGTERM)" : "sonarloop onboard: done",
      s, queue ? &*queue : nullptr);
  if (web) {
    web->hub.close();  // the last lines and statistics go out; then the counts are final
    print_web_summary(*web);
  }
  if (stats_json_file) {
    stats_json_file->write_and_close(onboard_stats_json(s, queue ? &*queue : nullptr) + "\n");
  }
  return 0;
}

}  // namespace

const Command kOnboardCommand{
    "onboard", "the onboard consumer: receive the sonar stream, detect, classify, report contacts",
    R"(usage: sonarloop onboard --listen HOST:PORT | --xtf FILE.xtf [--model MODEL] [options]

Receives the sonar stream of `sonarloop run --udp` (the XTF file header and one XTF ping per
UDP datagram), or reads a recorded .xtf file, and runs the onboard chain on it:
  receive    decode, put pings back in order (reorder window), count lost, late, duplicated,
             reordered and malformed datagrams
  waterfall  levels in dB re full scale with each ping's navigation
  detect     a strong highlight followed by an acoustic shadow deep below the local seabed
             level, tall enough for a mine-like object, one contact per object
  classify   chips cut as `sonarloop dataset` cuts them (3 m x 3 m, pixels of the model's
             resolution, one ping per row resampled along track with the navigation and
             pitch), classified by the PCA model of `sonarloop train` at the best alignment
  report     one JSON line per contact: time, ping, latitude/longitude of the object and its
             north/east metres from the scenario's origin (the frame of the scenario's
             scene.json and truth.json), class, mine / non-mine, the distance to every class,
             and for an object seen before the decision fused over its looks (atr/look_fusion.h)
Contacts go to stdout (or --contacts FILE) as they are found; statistics go to stderr at the
end. Without --model the objects are reported unclassified. With --listen, Ctrl-C stops
cleanly (objects still open are reported).

options:
  --listen HOST:PORT     receive UDP there (port 0: any free port; the port is printed)
  --xtf FILE.xtf         read a recorded stream instead (e.g. run --record DIR: DIR/pings.xtf)
  --model MODEL          a model of `sonarloop train` (highlight chips, e.g. 60 x 60 at 5 cm);
                         `default`: the default model of `sonarloop mission` (built and cached
                         the first time, docs/autonomy.md)
  --contacts FILE        write the contacts there (JSON Lines; default stdout); udp:HOST:PORT
                         sends each contact's JSON line as one UDP datagram there instead
                         (e.g. to `sonarloop autonomy --contacts`)
  --imc udp:HOST:PORT    also send each contact there as IMC (docs/formats.md §7): a CcuEvent
                         "map feature added" with a point of interest at the contact, the
                         mark a Neptus console offers to put on its map (contacts with a
                         latitude and longitude only)
  --imc-system ID        the IMC address the contacts come from (default 0x2050, the
                         emulated vehicle's of `run --imc`)
  --duration S           stop after S seconds of listening
  --idle-exit S          stop when no datagram has come for S seconds (after the first)
  --reorder-window N     pings held to put late datagrams back in order (default 32)
  --search-rows N        alignment search: chip windows tried up to N pixels along track
                         either side of the detector's centre (default 6)
  --search-cols N        the same in range (default 10)
  --detector-threshold H  the detector's operating threshold: the smallest object height, in
                         metres, measured from its shadow (default 0.14; atr/detector.h)
  --gate-threshold P     the classification gate's operating point, the target probability a
                         detection needs (0 to 1; default: the model's, chosen in training):
                         higher gives fewer false contacts and fewer targets (a mission
                         report's gate_froc.csv); for a model with gates (train --surveys)
  --look-radius M        multi-look fusion: a classified object within M metres of one seen
                         before (another pass or aspect) is fused with it, and its report adds
                         looks, object, fused_class and fused_mine_like (default 2; 0: off)
  --scenario FILE        the scenario flown (YAML; default: the embedded default scenario):
                         its origin is the origin of the contacts' north_m / east_m
  --origin LAT,LON       that origin given directly, in degrees; `--origin first-ping`: the
                         stream's first ping with a position fix (for recordings of no
                         scenario, e.g. real data; latitude and longitude 0, 0 is no fix)
  --stats-json FILE      write the final statistics as JSON
  --quiet                no start-up lines (warnings and the final statistics still print)
  --web HOST:PORT        serve the live operator view there (docs/web.md): waterfall, track,
                         contacts, statistics, pause; PORT alone binds 127.0.0.1, port 0 a
                         free port (the URL is printed). Read-only; a slow browser loses
                         lines, never delays the consumer. With --xtf the view ends when the
                         file is read

examples:
  sonarloop dataset --out out/chips --count 400 && sonarloop train out/chips --out out/atr.slpca
  sonarloop onboard --listen 127.0.0.1:5600 --model out/atr.slpca --contacts out/contacts.jsonl &
  sonarloop run --udp 127.0.0.1:5600 --rate 4
  sonarloop onboard --xtf out/run/pings.xtf --model out/atr.slpca
  sonarloop onboard --xtf survey.xtf --model real.slpca --origin first-ping
  sonarloop onboard --listen 127.0.0.1:5600 --model out/atr.slpca --web 8080
  sonarloop onboard --listen 127.0.0.1:5600 --model default --imc udp:127.0.0.1:6001
)",
    run_onboard, 15};
SONARLOOP_REGISTER_COMMAND(kOnboardCommand);

}  // namespace sonarloop::tools
