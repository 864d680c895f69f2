#pragma once
// The state behind Emulator (emulator.h), internal to the emulator library. Its members are
// defined by responsibility across four files:
//   emulator_setup.cpp   configuration: the options validated, the scene, sonar, trajectory and
//                        timing derived (configure), the outputs opened (open_outputs);
//   emulator_loop.cpp    the publisher's loop: pings and navigation merged in time order and paced,
//                        each sent and recorded (loop, publish_ping, publish_nav, drop_ping);
//   emulator_stats.cpp   the run's statistics and the description of its outputs;
//   emulator.cpp         start-up, run and shutdown, and the Emulator facade.
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/geodesy.h"
#include "drivers/n2k/sid.h"
#include "emulator/device.h"
#include "emulator/emulator.h"
#include "emulator/external_pose.h"
#include "emulator/nav_frames.h"
#include "emulator/ping_producer.h"
#include "emulator/pose_source.h"
#include "emulator/realtime_priority.h"
#include "emulator/recording.h"
#include "emulator/render_queue.h"
#include "sim/scene/scene.h"
#include "sim/vehicle/nav_sensor.h"
#include "sim/vehicle/trajectory.h"

namespace sonarloop::emulator {

struct Emulator::Impl {
  static constexpr SimTime kNever = std::numeric_limits<SimTime>::max();
  // Render workers make the scene this far ahead of the pings along the track (ping_producer.h).
  static constexpr double kPrepareAhead_m = 10.0;
  // Interval of the start-up progress lines (wall time).
  static constexpr std::int64_t kStartupProgressNs = 5'000'000'000;
  // Longest sleep of the publisher: bounds how long a stop request (SIGINT) waits.
  static constexpr std::int64_t kStopPollNs = 50'000'000;

  static double seconds(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }

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
  xtf::XtfFileHeader header;
  std::vector<std::uint8_t> header_bytes;
  std::size_t packet_bytes = 0;
  SimTime period = 0;
  SimTime send_delay = 0;
  SimTime end = 0;
  std::int64_t n_pings = 0;

  // the output devices (device.h), in the order they get each event: on the wire first
  std::vector<std::unique_ptr<Device>> devices;
  std::unique_ptr<PoseSource> pose_source;
  std::unique_ptr<ExternalPoseInput> external_pose;  // --pose-from: pings and navigation read it
  std::unique_ptr<ScenePingProducer> producer;
  std::unique_ptr<RenderQueue> queue;

  // ---- run state (publisher thread) ----
  RunStats stats;
  std::int64_t epoch_utc_ns = 0;
  std::int64_t cpu_start_ns = 0;
  std::array<can::CanFrame, kNavPgnCount> frames{};
  n2k::N2kSid sid;
  bool pings_stale = false;  // inside a stale episode (pings)
  SimTime sim_reached = 0;
  RealtimeOutcome realtime;  // --realtime-priority's outcome
  // The ping the publisher last found unrendered in its open send window: its lateness is the
  // render workers' (RunStats::pings_late_render), not the publisher's.
  std::int64_t unrendered_at_open = -1;

  void message(std::string_view text) const;
  bool stop_requested() const { return hooks.stop_requested && hooks.stop_requested(); }
  // When ping i's datagram is due, in simulation time: its ping time plus the receive window.
  SimTime send_time(std::int64_t i) const { return i * period + send_delay; }

  // emulator_setup.cpp
  void configure();
  void validate_options() const;
  void check_fits_datagram() const;
  void make_vehicle();
  void make_file_header();
  void set_timing();
  void open_outputs();
  void open_transports();
  void make_render_queue();

  // emulator_loop.cpp
  // What the publisher's loop sees at the top of one turn.
  struct Turn {
    std::int64_t now = 0;
    std::uint64_t generation = 0;  // the render queue's wake-up generation, read before `now`
    bool ping_left = false;
    bool nav_left = false;
    SimTime nav_t = 0;
    std::int64_t next_stats = 0;
  };
  void loop();
  void turn_max_rate(NavSchedule& navs, std::int64_t& k, const Turn& turn);
  void turn_paced(NavSchedule& navs, std::int64_t& k, const Turn& turn);
  void publish_nav(const NavSchedule::Sample& sample);
  vehicle::NavSolution measure_nav(SimTime t, NavPgnMask& due);
  void publish_ping(const PingSlot& slot, std::int64_t k);
  void note_stale_ping(const PingSlot& slot, std::int64_t k);
  void drop_ping(std::int64_t k);

  // emulator_stats.cpp
  void init_stats();
  void update_stats(std::int64_t now);
  std::vector<std::string> describe_outputs() const;

  // emulator.cpp
  RunStats run();
  void prepare_first_ping();
  void start_clock();
  void raise_priority();
  void shutdown();
};

}  // namespace sonarloop::emulator
