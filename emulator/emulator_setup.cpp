// Configuring a run (Emulator's constructor, emulator_impl.h): the options validated, then the
// scene, sonar, renderer, vehicle, XTF file header and timing derived from the scenario, and the
// outputs opened (UDP, CAN, recording, pose source, the render queue), so that every
// configuration error surfaces before anything is sent.
#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "drivers/xtf/xtf_codec.h"
#include "emulator/emulator_impl.h"
#include "emulator/imc_device.h"
#include "emulator/mcap_device.h"
#include "emulator/nav_can_device.h"
#include "emulator/recorder_device.h"
#include "emulator/sonar_udp_device.h"
#include "emulator/xtf_ping.h"
#include "sim/render/ping_renderer.h"

namespace sonarloop::emulator {
namespace {

// XTF ping packet: 256-byte ping header, 64-byte channel header, sizes padded to 64 bytes
// (docs/formats.md 1.7).
constexpr int kXtfPingHeaderBytes = 256;
constexpr int kXtfChannelHeaderBytes = 64;
constexpr int kXtfPadBytes = 64;

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

// ---- configuration ----

// In the order each step needs the ones before it: the vehicle plans over the scene, the timing
// needs the sonar and the trajectory's end.
void Emulator::Impl::configure() {
  construct_ns = clock.now_ns();
  validate_options();
  seabed::SeabedOptions seabed_options;
  seabed_options.cache_bytes = options.seabed_cache_bytes;
  scene = std::make_unique<scene::Scene>(scenario.scene, seabed_options);
  setup = render::make_sonar_setup(scenario.sonar, scenario.scene.water);
  check_fits_datagram();
  renderer = render::make_ping_renderer(options.renderer, setup);
  make_vehicle();
  make_file_header();
  set_timing();
  init_stats();
}

// The options that do not depend on the scenario; throws std::invalid_argument naming the option.
void Emulator::Impl::validate_options() const {
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
  if (!(options.deadline_tolerance_s > 0.0 && options.deadline_tolerance_s <= 10.0)) {
    throw std::invalid_argument("--lateness-tolerance-ms must be > 0 and at most 10000");
  }
  if (options.realtime_priority != 0 && (options.realtime_priority < kMinRealtimePriority ||
                                         options.realtime_priority > kMaxRealtimePriority)) {
    throw std::invalid_argument("--realtime-priority must be 1..99");
  }
}

// A ping must fit one UDP datagram (with --udp): throws std::invalid_argument naming the sonar, the
// largest samples per side that fit and what to change.
void Emulator::Impl::check_fits_datagram() const {
  if (!options.udp) return;
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

// The trajectory (planned over the seabed) and the navigation sensor models.
void Emulator::Impl::make_vehicle() {
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
}

// The XTF file header and the size of every ping packet (fixed by the sonar).
void Emulator::Impl::make_file_header() {
  header = make_xtf_file_header(setup, setup.desc.name, "sonarloop run " + scenario.scene.name);
  header_bytes = xtf::encode_file_header(header);
  // a blank ping of this sonar: its encoded size is every ping's
  render::PingLines lines;
  lines.port.assign(static_cast<std::size_t>(setup.bins), 0.0f);
  lines.stbd.assign(static_cast<std::size_t>(setup.bins), 0.0f);
  xtf::XtfPing ping;
  PingNav pn;
  pn.time_utc_ns = kMaxRateEpochUtcNs;
  make_xtf_ping(setup, header, lines, pn, ping);
  packet_bytes = xtf::encoded_ping_size(ping);
}

// The ping period, the send delay (the receive window), the end of the run and the ping count.
void Emulator::Impl::set_timing() {
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
}

// ---- outputs ----

void Emulator::Impl::open_outputs() {
  open_transports();
  make_render_queue();
}

// UDP, CAN, the recording and the pose source: errors name the option they come from.
void Emulator::Impl::open_transports() {
  if (options.udp) {
    devices.push_back(std::make_unique<SonarUdpDevice>(*options.udp, options.udp_send_buffer_bytes,
                                                       header_bytes, packet_bytes));
  }
  if (options.imc) {
    ImcSonarInfo info;
    info.frequency_hz = setup.desc.frequency_hz;
    info.max_range_m = setup.desc.max_range_m;
    devices.push_back(std::make_unique<ImcDevice>(*options.imc, ltp, info));
  }
  for (const std::string& spec : options.can_specs) {
    try {
      devices.push_back(std::make_unique<NavCanDevice>(can::open_can_transport(spec)));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(e.what());
    } catch (const std::exception& e) {
      const std::string what = e.what();
      throw std::runtime_error(what.find(spec) == std::string::npos ? "--can " + spec + ": " + what
                                                                    : what);
    }
  }
  if (options.record_dir) {
    devices.push_back(
        std::make_unique<RecorderDevice>(std::make_unique<Recording>(*options.record_dir, header),
                                         [this](const std::string& w) { message(w); }));
  }
  if (options.mcap_path) {
    McapSonarInfo info;
    info.frequency_hz = setup.desc.frequency_hz;
    info.sound_speed_m_s = setup.sound_speed_m_s;
    info.bin_size_m = setup.desc.bin_size_m;
    devices.push_back(std::make_unique<McapDevice>(*options.mcap_path, ltp, info));
  }
  if (options.pose_from) {
    Clock* c = &clock;
    PoseSourceOptions pose_options;
    pose_options.limits = pose_limits_for_scene(scenario.scene);
    // rejected poses and lost connections, said with the run's other warnings
    pose_options.on_warning = [this](const std::string& w) { message("warning: " + w); };
    try {
      pose_source = open_pose_source(
          *options.pose_from, ltp, [c] { return c->now_ns(); }, pose_options);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--pose-from: ") + e.what());
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("--pose-from: ") + e.what());
    }
  }
}

// The render workers' producer and the render-ahead queue (started by run(), at t = 0).
void Emulator::Impl::make_render_queue() {
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
  if (pose_source) {
    external_pose = std::make_unique<ExternalPoseInput>(
        *pose_source, pacer, clock, *trajectory, from_seconds(options.pose_delay_s),
        from_seconds(options.stale_after_s), scenario.scene.seed);
    ps.external = external_pose.get();
    ps.pacer = &pacer;
  }
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

}  // namespace sonarloop::emulator
