// Emulator (emulator.h): the facade over Emulator::Impl (emulator_impl.h), and the run's
// start-up, start of the clock and shutdown. Configuration is in emulator_setup.cpp, the
// publisher's loop in emulator_loop.cpp, the statistics in emulator_stats.cpp.
#include "emulator/emulator.h"

#include <cstdio>
#include <ctime>
#include <stdexcept>

#include "emulator/emulator_impl.h"
#include "sim/render/ping_renderer.h"

namespace sonarloop::emulator {

void Emulator::Impl::message(std::string_view text) const {
  if (hooks.message) {
    hooks.message(text);
  } else {
    std::fprintf(stderr, "%.*s\n", static_cast<int>(text.size()), text.data());
  }
}

RunStats Emulator::Impl::run() {
  try {
    prepare_first_ping();
    if (options.realtime_priority != 0) lock_process_memory(realtime);
    start_clock();
    raise_priority();
    loop();
  } catch (...) {
    shutdown();
    throw;
  }
  shutdown();
  update_stats(clock.now_ns());
  return stats;
}

// Start-up: what the first ping reads (its scene and the scene ahead), before the clock starts.
void Emulator::Impl::prepare_first_ping() {
  if (stop_requested()) throw StartupStopped();
  const std::int64_t t0 = clock.now_ns();
  producer->prepare(0, options.threads);
  if (stop_requested()) throw StartupStopped();
  char msg[160];
  std::snprintf(
      msg, sizeof msg, "%s renderer: scene for the first ping and %.0f m ahead made in %.3f s",
      render::renderer_name(options.renderer), kPrepareAhead_m, seconds(clock.now_ns() - t0));
  message(msg);
}

// --realtime-priority (realtime_priority.h): memory locked before t = 0 (locking faults in every
// page), SCHED_FIFO for this thread, the publisher, once the render workers run (threads inherit
// their creator's policy: they stay at normal priority).
void Emulator::Impl::raise_priority() {
  if (options.realtime_priority == 0) return;
  apply_fifo_priority(options.realtime_priority, realtime);
  for (const std::string& line : realtime.messages)
    message(line);
  stats.realtime = realtime.summary();
}

// t = 0: the epoch and the pacer's wall start, read together; then the render workers start.
void Emulator::Impl::start_clock() {
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

  const time_t secs = static_cast<time_t>(epoch_utc_ns / kNanosecondsPerSecond);
  tm utc{};
  gmtime_r(&secs, &utc);
  char when[64];
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &utc);
  char msg[160];
  std::snprintf(msg, sizeof msg, "running: t = 0 is %s (UTC); Ctrl-C stops cleanly", when);
  message(msg);
}

void Emulator::Impl::shutdown() {
  // the renderers first, then the outputs, so that the recordings are complete; the outputs in
  // the reverse order of their adding, so that one added later (the onboard consumer of `run
  // --classify`) can still hand its last results to one added before it (the MCAP recording)
  if (queue) queue->stop();
  std::string errors;
  for (auto d = devices.rbegin(); d != devices.rend(); ++d) {
    try {
      (*d)->close();
    } catch (const std::exception& e) {
      errors += std::string(errors.empty() ? "" : "; ") + e.what();
    }
  }
  if (!errors.empty()) message("warning: " + errors);
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

void Emulator::add_device(std::unique_ptr<Device> device) {
  if (!device) throw std::invalid_argument("add_device: no device");
  impl_->devices.push_back(std::move(device));
}

std::vector<Device*> Emulator::devices() const {
  std::vector<Device*> out;
  for (const auto& d : impl_->devices)
    out.push_back(d.get());
  return out;
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
  return impl_->describe_outputs();
}

}  // namespace sonarloop::emulator
