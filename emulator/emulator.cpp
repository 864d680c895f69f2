#include "emulator/emulator.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <stdexcept>

#include "drivers/n2k/sid.h"
#include "drivers/xtf/xtf_codec.h"
#include "emulator/nav_frames.h"
#include "emulator/ping_producer.h"
#include "emulator/pose_source.h"
#include "emulator/recording.h"
#include "emulator/render_queue.h"
#include "emulator/xtf_ping.h"
#include "sim/core/geodesy.h"
#include "sim/render/ping_renderer.h"
#include "sim/scene/scene.h"
#include "sim/vehicle/nav_sensor.h"
#include "sim/vehicle/trajectory.h"

namespace sonarloop::emulator {
namespace {

constexpr SimTime kNever = std::numeric_limits<SimTime>::max();
// Render workers make the scene this far ahead of the pings along the track (ping_producer.h).
constexpr double kPrepareAhead_m = 10.0;
// Interval of the start-up progress lines (wall time).
constexpr std::int64_t kStartupProgressNs = 5'000'000'000;
// Longest sleep of the publisher: bounds how long a stop request (SIGINT) waits.
constexpr std::int64_t kStopPollNs = 50'000'000;
// XTF ping packet: 256-byte ping header, 64-byte channel header, sizes padded to 64 bytes
// (docs/formats.md 1.7).
constexpr int kXtfPingHeaderBytes = 256;
constexpr int kXtfChannelHeaderBytes = 64;
constexpr int kXtfPadBytes = 64;

double seconds(std::int64_t ns) {
  return static_cast<double>(ns) * 1e-9;
}

void default_message(std::string_view text) {
  std::fprintf(stderr, "%.*s\n", static_cast<int>(text.size()), text.data());
}

int bytes_per_sample(render::SampleType t) {
  switch (t) {
    case render::SampleType::kUint8:
      return 1;
    case render::SampleType::kUint16:
    case render::SampleType::kInt16:
      return 2;
    case render::SampleType::kFloat32:
      return 4;
  }
  return 4;
}

const char* sample_type_name(render::SampleType t) {
  switch (t) {
    case render::SampleType::kUint8:
      return "uint8";
    case render::SampleType::kUint16:
      return "uint16";
    case render::SampleType::kInt16:
      return "int16";
    case render::SampleType::kFloat32:
      return "float32";
  }
  return "?";
}

}  // namespace

int max_udp_samples_per_side(int bytes_per_sample) {
  // the largest multiple of 64 within a datagram, less the headers, split over two channels
  const int limit = static_cast<int>(net::kMaxUdpDatagramBytes) / kXtfPadBytes * kXtfPadBytes;
  const int sample_bytes = limit - kXtfPingHeaderBytes - 2 * kXtfChannelHeaderBytes;
  return sample_bytes / (2 * bytes_per_sample);
}

struct Emulator::Impl {
  Impl(const Scenario& sc, const EmulatorOptions& opt, Clock& clk, EmulatorHooks h)
      : options(opt),
        clock(clk),
        hooks(std::move(h)),
        scenario(sc),
        ltp(GeoPoint{sc.scene.origin.latitude_deg, sc.scene.origin.longitude_deg}),
        pacer(clk, opt.rate) {}

  // ---- configuration (constructor) ----
  EmulatorOptions options;
  Clock& clock;
  EmulatorHooks hooks;
  Scenario scenario;
  LocalTangentPlane ltp;
  Pacer pacer;
  std::int64_t construct_ns = 0;

  std::unique_ptr<scene::Scene> scene;
  render::SonarSetup setup;
  std::unique_ptr<render::PingRenderer> renderer;
  std::unique_ptr<vehicle::Trajectory> trajectory;
  std::unique_ptr<vehicle::NavSensorModel> nav;
  std::unique_ptr<vehicle::NavSensorModel> exact_nav;  // --pose-from: the pose as navigation
  xtf::XtfFileHeader header;
  std::vector<std::uint8_t> header_bytes;
  std::size_t packet_bytes = 0;
  SimTime period = 0;
  SimTime send_delay = 0;
  SimTime end = 0;
  std::int64_t n_pings = 0;

  std::unique_ptr<net::UdpSender> udp;
  std::vector<std::unique_ptr<can::CanTransport>> cans;
  std::unique_ptr<Recording> recording;
  std::unique_ptr<PoseSource> pose_source;
  std::unique_ptr<ScenePingProducer> producer;
  std::unique_ptr<RenderQueue> queue;

  // ---- run state (publisher thread) ----
  RunStats stats;
  std::int64_t epoch_utc_ns = 0;
  std::int64_t cpu_start_ns = 0;
  std::array<can::CanFrame, kNavPgnCount> frames{};
  n2k::N2kSid sid;
  SimTime next_header_t = 0;
  bool header_sent = false;
  bool pings_stale = false;  // inside a stale episode (pings)
  SimTime sim_reached = 0;

  void message(std::string_view text) const {
    if (hooks.message) {
      hooks.message(text);
    } else {
      default_message(text);
    }
  }
  bool stop_requested() const { return hooks.stop_requested && hooks.stop_requested(); }

  void configure();
  void open_outputs();
  RunStats run();
  void loop();
  void shutdown();
  void publish_nav(const NavSchedule::Sample& sample);
  void publish_ping(const PingSlot& slot, std::int64_t k);
  void drop_ping(std::int64_t k);
  void check_recording();
  void update_stats(std::int64_t now);
};

void Emulator::Impl::configure() {
  construct_ns = clock.now_ns();
  if (options.threads < 1) throw std::invalid_argument("--threads must be at least 1");
  if (options.duration_s && !(*options.duration_s > 0.0)) {
    throw std::invalid_argument("--duration must be > 0 s");
  }
  if (!(options.stale_after_s > 0.0)) throw std::invalid_argument("--stale-after must be > 0 s");
  if (!(options.pose_delay_s >= 0.0 && options.pose_delay_s <= options.stale_after_s)) {
    throw std::invalid_argument("--pose-delay must be >= 0 s and at most --stale-after");
  }
  if (options.pose_from && options.rate.max) {
    throw std::invalid_argument(
        "--pose-from needs a paced rate (realtime or a factor): with --rate max there is no "
        "wall time to follow an external pose in");
  }
  if (options.ring_slots < 1) throw std::invalid_argument("ring_slots must be at least 1");

  scene = std::make_unique<scene::Scene>(scenario.scene);
  setup = render::make_sonar_setup(scenario.sonar, scenario.scene.water);

  // a ping must fit one UDP datagram
  if (options.udp) {
    const int bps = bytes_per_sample(setup.desc.sample_type);
    const int max_samples = max_udp_samples_per_side(bps);
    if (setup.bins > max_samples) {
      char msg[512];
      std::snprintf(msg, sizeof msg,
                    "sonar '%s': %d samples per side (max_range %.6g m / bin_size %.6g m) do not "
                    "fit one UDP datagram: with %s samples (%d byte%s) at most %d samples per "
                    "side fit in 65507 bytes. Use a coarser bin_size_cm, a shorter max_range_m, "
                    "sample_type uint8, or run without --udp (recording only)",
                    setup.desc.name.c_str(), setup.bins, setup.desc.max_range_m,
                    setup.desc.bin_size_m, sample_type_name(setup.desc.sample_type), bps,
                    bps == 1 ? "" : "s", max_samples);
      throw std::invalid_argument(msg);
    }
  }
  renderer = render::make_ping_renderer(options.renderer, setup);

  // the vehicle plans its depth on the seabed's large-scale relief (slope and pink noise): its
  // terrain following looks 50 m ahead and smooths over metres, so the centimetre textures and
  // the rocks are below its bandwidth, and planning a long line makes no heightmap tile
  const scene::Scene& sc = *scene;
  const double water_depth_m = scenario.scene.water.depth_m;
  const vehicle::SeabedDepthFn seabed_depth = [&sc, water_depth_m](double n, double e) {
    return water_depth_m - sc.seabed().base_elevation(n, e);
  };
  // a long path sampled finely takes minutes: report progress and honour a stop request
  if (stop_requested()) throw StartupStopped();
  std::int64_t next_progress_ns = clock.now_ns() + kStartupProgressNs;
  const vehicle::PlanProgressFn progress = [&](std::size_t done, std::size_t total) {
    if (stop_requested()) throw StartupStopped();
    const std::int64_t now = clock.now_ns();
    if (now < next_progress_ns || done == total) return;
    next_progress_ns = now + kStartupProgressNs;
    char msg[200];
    std::snprintf(msg, sizeof msg,
                  "preparing: sampling the seabed along the vehicle's path, %.0f %% (%zu of %zu "
                  "points; Ctrl-C stops)",
                  100.0 * static_cast<double>(done) / static_cast<double>(total), done, total);
    message(msg);
  };
  trajectory =
      std::make_unique<vehicle::Trajectory>(scenario.vehicle.trajectory, seabed_depth, progress);
  nav = std::make_unique<vehicle::NavSensorModel>(scenario.vehicle.nav, scenario.scene.seed);
  exact_nav =
      std::make_unique<vehicle::NavSensorModel>(vehicle::NavNoiseDesc{}, scenario.scene.seed);

  header = make_xtf_file_header(setup, setup.desc.name, "sonarloop run " + scenario.scene.name);
  header_bytes = xtf::encode_file_header(header);
  {
    // the size of every ping packet (fixed by the sonar)
    render::PingLines lines;
    lines.port.assign(static_cast<std::size_t>(setup.bins), 0.0f);
    lines.stbd.assign(static_cast<std::size_t>(setup.bins), 0.0f);
    xtf::XtfPing ping;
    PingNav pn;
    pn.time_utc_ns = kMaxRateEpochUtcNs;
    make_xtf_ping(setup, header, lines, pn, ping);
    packet_bytes = xtf::encoded_ping_size(ping);
  }

  period = from_seconds(setup.ping_period_s);
  if (period <= 0) throw std::invalid_argument("the sonar's ping period must be > 0");
  const double slant_range_m = static_cast<double>(setup.bins) * setup.desc.bin_size_m;
  send_delay = std::min(period, from_seconds(2.0 * slant_range_m / setup.sound_speed_m_s));
  if (options.duration_s) {
    end = from_seconds(*options.duration_s);
  } else if (options.pose_from) {
    end = kNever;
  } else {
    end = trajectory->end_time();
  }
  if (end <= 0) throw std::invalid_argument("the run's duration is zero (trajectory too short?)");
  n_pings = end == kNever ? kNever : (end - 1) / period + 1;  // pings with k·T < end

  stats.rate = to_string(options.rate);
  stats.threads = options.threads;
  stats.ring_slots = options.ring_slots;
  stats.ping_period_s = seconds(period);
  stats.send_delay_s = seconds(send_delay);
  stats.bins_per_side = setup.bins;
  stats.bin_size_m = setup.desc.bin_size_m;
  stats.max_range_m = setup.desc.max_range_m;
  stats.packet_bytes = packet_bytes;
}

void Emulator::Impl::open_outputs() {
  if (options.udp) {
    udp = std::make_unique<net::UdpSender>(*options.udp, options.udp_send_buffer_bytes);
  }
  for (const std::string& spec : options.can_specs) {
    try {
      cans.push_back(can::open_can_transport(spec));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(e.what());
    } catch (const std::exception& e) {
      const std::string what = e.what();
      throw std::runtime_error(what.find(spec) == std::string::npos ? "--can " + spec + ": " + what
                                                                    : what);
    }
  }
  if (options.record_dir) recording = std::make_unique<Recording>(*options.record_dir, header);
  if (options.pose_from) {
    Clock* c = &clock;
    try {
      pose_source = open_pose_source(*options.pose_from, ltp, [c] { return c->now_ns(); });
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--pose-from: ") + e.what());
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("--pose-from: ") + e.what());
    }
  }

  PingProducerSetup ps;
  ps.renderer = renderer.get();
  ps.scene = scene.get();
  ps.trajectory = trajectory.get();
  ps.nav = nav.get();
  ps.ltp = &ltp;
  ps.header = &header;
  ps.clock = &clock;
  ps.seed = scenario.scene.seed;
  ps.ping_period_ns = period;
  ps.threads = options.threads;
  ps.prepare_ahead_m = kPrepareAhead_m;
  ps.pose_source = pose_source.get();
  ps.pacer = &pacer;
  ps.stale_after_ns = from_seconds(options.stale_after_s);
  ps.pose_delay_ns = from_seconds(options.pose_delay_s);
  producer = std::make_unique<ScenePingProducer>(ps);
  queue =
      std::make_unique<RenderQueue>(*producer, options.ring_slots, options.threads, packet_bytes);
  // paced: ping k is dropped when ping k + 1's send window opens (loop(), ping_window); the
  // pacer's wall start is set before the queue starts
  if (pacer.paced()) {
    queue->set_deadlines(
        [this](std::int64_t k) { return pacer.wall_of((k + 1) * period + send_delay); }, clock);
  }
}

void Emulator::Impl::update_stats(std::int64_t now) {
  stats.sim_time_s = seconds(sim_reached);
  stats.wall_time_s = seconds(now - pacer.wall_start_ns());
  stats.cpu_time_s = seconds(clock.process_cpu_ns() - cpu_start_ns);
  stats.pings_due = stats.pings_sent + stats.pings_dropped + stats.pings_stale;
  stats.pings_rendered = queue->produced();
  stats.render_mean_ms = stats.pings_rendered ? static_cast<double>(queue->produce_total_ns()) *
                                                    1e-6 / static_cast<double>(stats.pings_rendered)
                                              : 0.0;
  stats.render_max_ms = static_cast<double>(queue->produce_max_ns()) * 1e-6;
  stats.tiles_made = scene->seabed().tiles_made();
  if (udp) {
    stats.udp_dropped = udp->dropped();
  }
  if (recording) stats.recorded_pings = recording->pings();
}

void Emulator::Impl::publish_nav(const NavSchedule::Sample& sample) {
  const SimTime t = sample.t;
  stats.nav_frames_skipped += static_cast<std::uint64_t>(sample.skipped);
  NavPgnMask due = sample.due;
  vehicle::NavSolution solution;
  solution.t = t;
  if (pose_source) {
    // as the pings: the pose of the sample's own time less the delay
    const std::optional<ExternalPose> ext = pose_source->pose_at(
        pacer.wall_of(t) - from_seconds(options.pose_delay_s), from_seconds(options.stale_after_s));
    const std::int64_t age = ext ? clock.now_ns() - ext->received_ns : -1;
    if (!ext || age > from_seconds(options.stale_after_s)) {
      // no pose to publish: only what does not depend on it
      const NavPgnMask kept = due & pose_free_pgns();
      stats.nav_frames_withheld += static_cast<std::uint64_t>(std::popcount(due & ~kept));
      due = kept;
    } else {
      vehicle::VehicleState state = merge_external_pose(trajectory->state_at(t), *ext);
      // an external pose without altitude: the altimeter's (the DVL's) reading of the scene, the
      // height above the seabed's large-scale relief (as the vehicle's depth planning sees it)
      if (!std::isfinite(state.altitude_m)) {
        const Vec3& p = state.pose.position_W;
        state.altitude_m =
            scenario.scene.water.depth_m - scene->seabed().base_elevation(p.x(), p.y()) - p.z();
      }
      solution = exact_nav->measure(state);
    }
  } else {
    solution = nav->measure(trajectory->state_at(t));
  }
  const std::int64_t utc = epoch_utc_ns + t;
  const std::size_t n = make_nav_frames(solution, ltp, utc, sid.current(), due, frames);
  for (auto& c : cans)
    for (std::size_t i = 0; i < n; ++i)
      c->send(frames[i], utc);
  if (recording) {
    for (std::size_t i = 0; i < n; ++i)
      recording->write_nav(frames[i], utc);
    check_recording();
  }
  sid.advance();
  ++stats.nav_samples;
  stats.nav_frames += n;
  sim_reached = std::max(sim_reached, t);
  if (pacer.paced()) stats.nav_lateness.add(clock.now_ns() - pacer.wall_of(t));
}

void Emulator::Impl::publish_ping(const PingSlot& slot, std::int64_t k) {
  sim_reached = std::max(sim_reached, slot.truth.t);
  if (!slot.emitted) {
    ++stats.pings_stale;
    if (!pings_stale) {
      pings_stale = true;
      ++stats.stale_episodes;
      char msg[256];
      if (slot.truth.pose_age_ns < 0) {
        std::snprintf(msg, sizeof msg,
                      "warning: no pose received yet from %s: no pings until one arrives",
                      pose_source ? pose_source->describe().c_str() : "the pose source");
      } else {
        std::snprintf(msg, sizeof msg,
                      "warning: the external pose is stale (last update %.2f s ago, limit %.2f s):"
                      " pings paused at ping %lld until a fresh pose arrives",
                      seconds(slot.truth.pose_age_ns), options.stale_after_s,
                      static_cast<long long>(k));
      }
      message(msg);
    }
    return;
  }
  if (pings_stale) {
    pings_stale = false;
    char msg[128];
    std::snprintf(msg, sizeof msg, "external pose fresh again: pings resumed at ping %lld",
                  static_cast<long long>(k));
    message(msg);
  }
  const std::span<const std::uint8_t> packet(slot.packet.data(), slot.packet_size);
  if (udp) {
    if (!header_sent || slot.truth.t >= next_header_t) {
      udp->send(header_bytes);
      header_sent = true;
      next_header_t = slot.truth.t + from_seconds(kHeaderRepeatS);
      ++stats.udp_header_datagrams;
      ++stats.udp_datagrams;
      stats.udp_bytes += header_bytes.size();
    }
    udp->send(packet);
    ++stats.udp_datagrams;
    stats.udp_bytes += packet.size();
  }
  if (hooks.on_ping) hooks.on_ping(packet);
  if (slot.truth.pose_extrapolated) ++stats.pings_extrapolated;
  if (pacer.paced()) {
    const std::int64_t sent = clock.now_ns();
    const std::int64_t lateness = sent - pacer.wall_of(slot.truth.t + send_delay);
    stats.ping_lateness.add(lateness);
    stats.ping_latency.add(sent - pacer.wall_of(slot.truth.t));
    if (lateness > kDeadlineToleranceNs) ++stats.pings_late;
  }
  if (recording) {
    recording->write_ping(slot);
    check_recording();
  }
  ++stats.pings_sent;
}

void Emulator::Impl::check_recording() {
  // a write error (a full disk) stops the recording, not the run: said once, when it happens
  if (!stats.recording_error.empty() || recording->error().empty()) return;
  stats.recording_error = recording->error();
  message("warning: --record stopped: " + stats.recording_error +
          " (the run goes on; the recordings end with whole lines and packets)");
}

void Emulator::Impl::drop_ping(std::int64_t k) {
  ++stats.pings_dropped;
  sim_reached = std::max(sim_reached, k * period);
  queue->release(k);
}

void Emulator::Impl::loop() {
  NavSchedule navs;
  std::int64_t k = 0;
  const std::int64_t interval_ns =
      options.stats_interval_s > 0 ? from_seconds(options.stats_interval_s) : kNever;
  std::int64_t next_stats = interval_ns == kNever ? kNever : pacer.wall_start_ns() + interval_ns;
  auto send_time = [&](std::int64_t i) { return i * period + send_delay; };

  for (;;) {
    if (stop_requested()) break;
    if (queue->failed()) throw std::runtime_error(queue->error());
    const bool ping_left = k < n_pings;
    const SimTime nav_t = navs.next_time();
    const bool nav_left = nav_t < end;
    if (!ping_left && !nav_left) break;
    // read the wake-up generation before looking at the queue, so no notification is lost
    const std::uint64_t generation = queue->wakeup().generation();
    const std::int64_t now = clock.now_ns();
    if (now >= next_stats) {
      update_stats(now);
      if (hooks.on_stats) hooks.on_stats(stats);
      next_stats = interval_ns == kNever ? kNever : next_deadline(next_stats, interval_ns, now);
    }

    if (!pacer.paced()) {
      // as fast as possible, strictly in time order: navigation first at equal times
      if (nav_left && (!ping_left || nav_t <= send_time(k))) {
        publish_nav(navs.pop(nav_t));
        continue;
      }
      if (const PingSlot* slot = queue->ready(k)) {
        publish_ping(*slot, k);
        queue->release(k);
        ++k;
        continue;
      }
      queue->wakeup().wait_until(std::min(now + kStopPollNs, next_stats), generation);
      continue;
    }

    // paced: every event at its deadline
    if (nav_left && now >= pacer.wall_of(nav_t)) {
      publish_nav(navs.pop(pacer.sim_of(now)));
      continue;
    }
    std::int64_t wake = std::min(now + kStopPollNs, next_stats);
    if (nav_left) wake = std::min(wake, pacer.wall_of(nav_t));
    bool waiting_for_render = false;
    if (ping_left) {
      const std::int64_t open = pacer.wall_of(send_time(k));
      const std::int64_t close = pacer.wall_of(send_time(k + 1));
      switch (ping_window(open, close, now)) {
        case PingWindow::kMissed:
          drop_ping(k);
          ++k;
          continue;
        case PingWindow::kOpen:
          if (const PingSlot* slot = queue->ready(k)) {
            publish_ping(*slot, k);
            queue->release(k);
            ++k;
            continue;
          }
          waiting_for_render = true;  // late: sent as soon as it is rendered, until `close`
          wake = std::min(wake, close);
          break;
        case PingWindow::kEarly:
          wake = std::min(wake, open);
          break;
      }
    }
    if (waiting_for_render) {
      queue->wakeup().wait_until(wake, generation);
    } else {
      clock.sleep_until(wake);
    }
  }
}

void Emulator::Impl::shutdown() {
  // the renderers first, then the outputs, so that the recordings are complete
  if (queue) queue->stop();
  std::string errors;
  for (auto& c : cans) {
    try {
      c->flush();
    } catch (const std::exception& e) {
      errors += std::string(errors.empty() ? "" : "; ") + e.what();
    }
  }
  if (recording) {
    try {
      recording->close();
    } catch (const std::exception& e) {
      errors += std::string(errors.empty() ? "" : "; ") + e.what();
    }
  }
  if (!errors.empty()) message("warning: " + errors);
}

RunStats Emulator::Impl::run() {
  try {
    // start-up: what the first ping reads, before the clock starts
    if (stop_requested()) throw StartupStopped();
    const std::int64_t t0 = clock.now_ns();
    producer->prepare(0, options.threads);
    if (stop_requested()) throw StartupStopped();
    char msg[160];
    std::snprintf(
        msg, sizeof msg, "%s renderer: scene for the first ping and %.0f m ahead made in %.3f s",
        render::renderer_name(options.renderer), kPrepareAhead_m, seconds(clock.now_ns() - t0));
    message(msg);

    // t = 0: the epoch and the pacer's wall start, read together
    const std::int64_t wall_start = clock.now_ns();
    epoch_utc_ns = options.epoch_utc_ns ? *options.epoch_utc_ns
                   : options.rate.max   ? kMaxRateEpochUtcNs
                                        : clock.utc_now_ns();
    pacer.start_at(wall_start);
    stats.epoch_utc_ns = epoch_utc_ns;
    stats.startup_s = seconds(wall_start - construct_ns);
    cpu_start_ns = clock.process_cpu_ns();
    producer->set_epoch_utc_ns(epoch_utc_ns);
    queue->start(0, n_pings);
    {
      const time_t secs = static_cast<time_t>(epoch_utc_ns / kNanosecondsPerSecond);
      tm utc{};
      gmtime_r(&secs, &utc);
      char when[64];
      std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &utc);
      std::snprintf(msg, sizeof msg, "running: t = 0 is %s (UTC); Ctrl-C stops cleanly", when);
      message(msg);
    }

    loop();
  } catch (...) {
    shutdown();
    throw;
  }
  shutdown();
  update_stats(clock.now_ns());
  return stats;
}

// ---- Emulator ----

Emulator::Emulator(const Scenario& scenario, const EmulatorOptions& options, Clock& clock,
                   EmulatorHooks hooks)
    : impl_(std::make_unique<Impl>(scenario, options, clock, std::move(hooks))) {
  impl_->configure();
  if (impl_->stop_requested()) throw StartupStopped();
  impl_->open_outputs();
}

Emulator::~Emulator() {
  if (impl_) impl_->shutdown();
}

RunStats Emulator::run() {
  return impl_->run();
}

const render::SonarSetup& Emulator::sonar() const {
  return impl_->setup;
}
const xtf::XtfFileHeader& Emulator::file_header() const {
  return impl_->header;
}
SimTime Emulator::ping_period_ns() const {
  return impl_->period;
}
SimTime Emulator::send_delay_ns() const {
  return impl_->send_delay;
}
std::size_t Emulator::packet_bytes() const {
  return impl_->packet_bytes;
}
SimTime Emulator::end_time() const {
  return impl_->end;
}

std::vector<std::string> Emulator::describe_outputs() const {
  std::vector<std::string> out;
  char buf[256];
  if (impl_->udp) {
    std::snprintf(buf, sizeof buf,
                  "%s: one XTF ping per datagram (%zu bytes), file header (%zu bytes) first and "
                  "every %.0f s",
                  impl_->udp->describe().c_str(), impl_->packet_bytes, impl_->header_bytes.size(),
                  kHeaderRepeatS);
    out.emplace_back(buf);
  }
  for (const auto& c : impl_->cans)
    out.push_back("can: " + c->describe() + " (NMEA 2000 navigation)");
  if (impl_->recording) {
    out.push_back("record: " + impl_->recording->dir() + "/{pings.xtf, nav.log, truth.csv}");
  }
  if (impl_->pose_source) {
    std::snprintf(buf, sizeof buf,
                  "pose from %s (pings at the pose of their time less %.3g s; "
                  "stale after %.3g s)",
                  impl_->pose_source->describe().c_str(), impl_->options.pose_delay_s,
                  impl_->options.stale_after_s);
    out.emplace_back(buf);
  }
  return out;
}

}  // namespace sonarloop::emulator
