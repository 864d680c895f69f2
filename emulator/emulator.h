#pragma once
// The real-time emulator (`sonarloop run`): flies the scenario's vehicle along its trajectory
// (or follows an external pose, --pose-from), renders each ping at the sonar's ping period,
// streams it as one XTF packet per UDP datagram, publishes the navigation as NMEA 2000 frames on
// CAN, and records both.
//
// Threads
//   publisher (the caller of run()): the only thread that sends and records, through the
//   output devices (device.h: the UDP stream, each CAN transport, the recorder). It merges two
//     schedules in simulation time and paces them with absolute deadlines (pacer.h):
//     - ping k: ping time t_k = k·T (T = ping period); its datagram is due at the send time
//       s_k = t_k + W, W = the receive window 2·R/c (slant range R of the last sample, sound
//       speed c): a real sidescan has its ping's last echo then. Ping k may be sent in
//       [s_k, s_{k+1}) (pacer.h ping_window); a ping not rendered by s_{k+1} is dropped.
//     - navigation samples (nav_frames.h), each PGN at its standard rate, due at their sample
//       time; built from NavSensorModel::measure(state_at(t)) on the publisher thread.
//     Events are handled in time order, navigation first at equal times.
//   render workers (--threads): render pings ahead into the RenderQueue ring (render_queue.h,
//     ping_producer.h), and make the scene ahead of them (heightmap tiles for the profile
//     renderer, Embree views for the ray tracer); a late ping never blocks navigation.
//   transports' own threads (socketcand server), pose source thread (--pose-from).
//
// UDP stream (--udp HOST:PORT): the 1024-byte XTF file header as one datagram first, then again
// before the first ping at or after every kHeaderRepeatS (sonar_udp_device.h) of simulation
// time since the last one (a receiver that starts late learns the channel layout within 2 s);
// then one datagram per ping. Receivers tell them apart by size and first byte
// (xtf::classify_datagram).
// Datagram size: a ping must fit one datagram (65,507 bytes): the constructor refuses a sonar
// whose encoded ping is larger, naming the largest samples per side for its sample type
// (max_udp_samples_per_side: 32,544 uint8, 16,272 uint16, 8,136 float32). Without --udp there
// is no limit (recording only).
//
// Rates: realtime (deadlines = wall time), X (X times faster), max (no deadlines: every ping and
// frame in order as fast as rendering allows; nothing is dropped, so the output depends only on
// the scenario: byte-identical pings.xtf, nav.log and truth.csv on any number of threads).
// Epoch (UTC of t = 0): the wall clock at the start for paced rates, kMaxRateEpochUtcNs for
// --rate max (reproducible), or --epoch.
//
// Stop: run() returns when the duration is over or when hooks.stop_requested() turns true
// (SIGINT/SIGTERM; checked at least every 50 ms); recordings are flushed and closed either way.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/can/can_transport.h"
#include "drivers/net/host_port.h"
#include "drivers/net/udp_sender.h"
#include "drivers/xtf/xtf_types.h"
#include "emulator/device.h"
#include "emulator/imc_device.h"
#include "emulator/mcap_device.h"
#include "emulator/pacer.h"
#include "emulator/run_stats.h"
#include "sim/render/ping_renderer.h"
#include "sim/render/sonar.h"
#include "sim/scenario.h"

namespace sonarloop::emulator {

// Epoch of --rate max runs: 2026-01-01T00:00:00Z (as `sonarloop render`).
inline constexpr std::int64_t kMaxRateEpochUtcNs = 1767225600LL * 1'000'000'000LL;

struct EmulatorOptions {
  std::optional<double> duration_s;     // simulation seconds; default: the trajectory's duration
                                        // (without end with --pose-from)
  std::optional<net::HostPort> udp;     // --udp
  std::optional<ImcDeviceOptions> imc;  // --imc (imc_device.h)
  std::vector<std::string> can_specs;   // --can, each opened with can::open_can_transport
  std::optional<std::string> record_dir;
  std::optional<std::string> mcap_path;  // the MCAP recording (mcap_device.h)
  Rate rate;
  int threads = 1;  // render workers
  std::optional<std::string> pose_from;
  double stale_after_s = 2.0;
  double pose_delay_s = 0.1;  // --pose-delay: pings at the pose of their time less this
  std::optional<std::int64_t> epoch_utc_ns;
  double stats_interval_s = 5.0;  // live statistics every this many wall seconds (0: never)
  render::RendererKind renderer = render::RendererKind::kProfile;  // --renderer
  int ring_slots = 16;                                             // render-ahead depth (pings)
  // what the seabed's tile caches may hold (--memory-budget; seabed_model.h)
  std::size_t seabed_cache_bytes = seabed::kDefaultSeabedCacheBytes;
  int udp_send_buffer_bytes = 1 << 20;
  // a ping sent more than this after its send time is a deadline miss (--lateness-tolerance-ms)
  double deadline_tolerance_s = static_cast<double>(kDefaultDeadlineToleranceNs) * 1e-9;
  // --realtime-priority: SCHED_FIFO at this priority (1..99) for the publisher thread and locked
  // memory, where permitted (realtime_priority.h); 0: normal priority
  int realtime_priority = 0;
};

struct EmulatorHooks {
  // Start-up information and warnings, one line each (default: stderr). With --pose-from it is
  // also called from the pose source's thread (its warnings: rejected poses, a lost connection).
  std::function<void(std::string_view)> message;
  // Periodic statistics (default: none); devices get them too (Device::stats).
  std::function<void(const RunStats&)> on_stats;
  // Polled by the publisher; true stops the run (SIGINT/SIGTERM).
  std::function<bool()> stop_requested;
};

// Largest samples per side for which a two-channel ping of `bytes_per_sample` fits one UDP
// datagram (net::kMaxUdpDatagramBytes), with XTF's 64-byte padding.
int max_udp_samples_per_side(int bytes_per_sample);

// Thrown by the constructor or run() when hooks.stop_requested() turns true during start-up
// (building the scene, planning a long trajectory, the first ping's scene): nothing was sent.
class StartupStopped : public std::runtime_error {
 public:
  StartupStopped() : std::runtime_error("stopped during start-up (nothing sent)") {}
};

class Emulator {
 public:
  // Loads nothing itself: the scenario is given. Opens every output (UDP, CAN, recording, pose
  // source) so that configuration errors surface here with a clear message: std::invalid_argument
  // (bad option values, a ping too large for a datagram) or std::runtime_error (a port in use,
  // no kernel CAN, a directory that cannot be created).
  Emulator(const Scenario& scenario, const EmulatorOptions& options, Clock& clock,
           EmulatorHooks hooks = {});
  ~Emulator();
  Emulator(const Emulator&) = delete;
  Emulator& operator=(const Emulator&) = delete;

  // Adds a device of the caller's (device.h), before run(): it gets every event after the
  // emulator's own devices (the UDP stream, the CAN transports, the recorder), and the periodic
  // statistics; the emulator owns it from now on. `run --classify` and `run --web` add theirs.
  void add_device(std::unique_ptr<Device> device);
  // The devices, the emulator's own first, then those added, in order.
  std::vector<Device*> devices() const;
  // The first device of type D (nullptr: none), e.g. the MCAP recording to add contacts to.
  template <class D>
  D* find_device() const {
    for (Device* d : devices())
      if (auto* found = dynamic_cast<D*>(d)) return found;
    return nullptr;
  }

  // Runs to the end of the duration or until stopped; returns the final statistics.
  RunStats run();

  const render::SonarSetup& sonar() const;
  const xtf::XtfFileHeader& file_header() const;
  SimTime ping_period_ns() const;
  SimTime send_delay_ns() const;
  std::size_t packet_bytes() const;
  // The end of the run in simulation time (INT64_MAX: until stopped).
  SimTime end_time() const;
  // Every output, one line each ("udp to 127.0.0.1:5600", "socketcand server on ...").
  std::vector<std::string> describe_outputs() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sonarloop::emulator
