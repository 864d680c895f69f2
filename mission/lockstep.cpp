#include "mission/lockstep.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "common/parallel_for.h"
#include "drivers/xtf/xtf_codec.h"
#include "emulator/emulator.h"
#include "emulator/xtf_ping.h"
#include "sim/core/sim_time.h"
#include "sim/scene/scene.h"
#include "sim/vehicle/nav_sensor.h"

namespace sonarloop::mission {
namespace {

// One ping of a batch: its index, the true state it is flown from, what it becomes.
struct PingJob {
  std::int64_t k = 0;
  vehicle::VehicleState state;
  render::PingLines lines;
  xtf::XtfPing xtf;
  std::vector<std::uint8_t> packet;
  std::size_t packet_size = 0;
};

// The simulator's state of the agent's vehicle at time t (its pose as `run --pose-from udp:`
// would take it: position, depth, heading, pitch; no roll).
vehicle::VehicleState sim_state(const autonomy::VehicleState& a, double speed_m_s, SimTime t) {
  vehicle::VehicleState s;
  s.t = t;
  s.pose.position_W = Vec3(a.position.north_m, a.position.east_m, a.depth_m);
  s.pose.yaw = a.heading_rad;
  s.pose.pitch = a.pitch_rad;
  s.pose.roll = 0.0;
  s.speed_m_s = speed_m_s;
  s.velocity_W = Vec3(speed_m_s * std::cos(a.heading_rad), speed_m_s * std::sin(a.heading_rad),
                      -speed_m_s * std::tan(a.pitch_rad));
  s.yaw_rate = a.turn_rate_rad_s;
  return s;
}

}  // namespace

void LockstepOptions::validate() const {
  if (threads < 1) throw std::invalid_argument("lock-step: threads must be at least 1");
  if (!(batch_s > 0.0 && batch_s <= 60.0)) {
    throw std::invalid_argument("lock-step: batch must be in (0, 60] s");
  }
  if (!(drain_s >= 0.0 && std::isfinite(drain_s))) {
    throw std::invalid_argument("lock-step: drain must be >= 0 s");
  }
  if (!(max_duration_s > 0.0)) throw std::invalid_argument("lock-step: max duration must be > 0 s");
}

LockstepResult run_lockstep(const Scenario& scenario, const scene::Scene& scene,
                            std::optional<atr::Model> model, const atr::OnboardOptions& onboard,
                            autonomy::Agent& agent, const LockstepOptions& options,
                            const LockstepHooks& hooks) {
  options.validate();
  const render::SonarSetup setup = render::make_sonar_setup(scenario.sonar, scenario.scene.water);
  const std::unique_ptr<render::PingRenderer> renderer =
      render::make_ping_renderer(options.renderer, setup);
  const xtf::XtfFileHeader header = emulator::make_xtf_file_header(
      setup, setup.desc.name, "sonarloop mission " + scenario.scene.name);
  const GeoPoint origin{scenario.scene.origin.latitude_deg, scenario.scene.origin.longitude_deg};
  const LocalTangentPlane ltp(origin);
  const vehicle::NavSensorModel nav(scenario.vehicle.nav, scenario.scene.seed);
  const double period_s = setup.ping_period_s;
  if (!(period_s > 0.0)) throw std::invalid_argument("lock-step: the sonar's ping period is 0");
  const double water_depth_m = scenario.scene.water.depth_m;
  const double speed_m_s = scenario.vehicle.trajectory.speed_m_s;
  // the altimeter: the seabed's depth below the surface under the vehicle (large-scale relief)
  const auto seabed_depth = [&](const autonomy::Point2& p) -> std::optional<double> {
    return water_depth_m - scene.seabed().base_elevation(p.north_m, p.east_m);
  };

  LockstepResult result;
  std::vector<atr::Contact> arrived;  // reported during the current batch
  atr::OnboardOptions oo = onboard;
  oo.frame_origin = origin;
  atr::OnboardPipeline pipeline(std::move(model), oo, [&](const atr::Contact& c) {
    arrived.push_back(c);
    result.contacts.push_back(c);
    if (hooks.on_contact) hooks.on_contact(c);
  });
  pipeline.set_candidate_sink([&](const atr::CandidateReport& r) {
    result.candidates.push_back(r);
    if (hooks.on_candidate) hooks.on_candidate(pipeline.waterfall(), r);
  });
  const std::vector<std::uint8_t> header_bytes = xtf::encode_file_header(header);
  pipeline.feed(header_bytes);
  if (hooks.on_packet) hooks.on_packet(header_bytes);

  std::vector<render::PingScratch> scratch(static_cast<std::size_t>(options.threads));
  std::vector<PingJob> jobs;
  std::int64_t k = 0;  // the next ping
  double batch_end_s = 0.0;
  double done_at_s = -1.0;
  for (;;) {
    if (hooks.stop_requested && hooks.stop_requested()) {
      result.stopped = true;
      break;
    }
    // 1. the previous batch's contacts
    std::vector<atr::Contact> deliver;
    deliver.swap(arrived);
    for (const atr::Contact& c : deliver)
      agent.on_contact(c);
    // 2. the agent to each ping time of the batch
    batch_end_s += options.batch_s;
    std::size_t n = 0;
    for (;; ++k, ++n) {
      const double t_s = static_cast<double>(k) * period_s;
      if (t_s > batch_end_s) break;
      agent.step(t_s - agent.state().t_s, seabed_depth(agent.state().position));
      if (jobs.size() <= n) jobs.emplace_back();
      jobs[n].k = k;
      jobs[n].state = sim_state(agent.state(), speed_m_s, from_seconds(t_s));
    }
    agent.step(batch_end_s - agent.state().t_s, seabed_depth(agent.state().position));
    // 3. render and encode
    parallel_for(n, options.threads, [&](std::size_t i, int w) {
      PingJob& j = jobs[i];
      renderer->render(scene, j.state.pose, scenario.scene.seed, static_cast<std::uint64_t>(j.k),
                       {}, scratch[static_cast<std::size_t>(w)], j.lines);
      const vehicle::NavSolution sol = nav.measure(j.state);
      const emulator::PingNav pn =
          emulator::ping_nav_of(sol, ltp, emulator::kMaxRateEpochUtcNs + j.state.t,
                                j.lines.altitude_m, static_cast<std::uint32_t>(j.k));
      emulator::make_xtf_ping(setup, header, j.lines, pn, j.xtf);
      j.packet.resize(xtf::encoded_ping_size(j.xtf));
      j.packet_size = xtf::encode_ping(j.xtf, header, j.packet);
    });
    // 4. the onboard consumer, in ping order
    for (std::size_t i = 0; i < n; ++i) {
      const PingJob& j = jobs[i];
      const std::span<const std::uint8_t> packet(j.packet.data(), j.packet_size);
      pipeline.feed(packet);
      if (hooks.on_packet) hooks.on_packet(packet);
      const Pose& p = j.state.pose;
      result.pings.push_back(study::SwathPing{to_seconds(j.state.t), p.position_W.x(),
                                              p.position_W.y(), p.yaw, j.lines.altitude_m});
    }
    if (hooks.on_batch) hooks.on_batch(agent);
    const double now_s = agent.state().t_s;
    if (agent.mission_done()) {
      if (done_at_s < 0.0) done_at_s = now_s;
      if (now_s - done_at_s >= options.drain_s) break;
    } else {
      done_at_s = -1.0;
    }
    if (now_s >= options.max_duration_s) break;
  }
  result.mission_s = agent.state().t_s;
  result.onboard = pipeline.stats();
  return result;
}

}  // namespace sonarloop::mission
