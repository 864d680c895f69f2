#pragma once
// The closed loop in lock-step (ours; docs/autonomy.md, "Lock-step missions"): the emulator's
// renderer, the onboard consumer and the autonomy agent in one process, advanced together in
// simulation time. Nothing reads a wall clock and nothing crosses a socket, so a mission is a
// pure function of (scenario, seed, model, options): the same report at any speed, on a loaded
// machine or an idle one, with one render thread or several, and no ping is ever dropped (the
// loop waits for its renders instead of keeping a deadline).
//
// Why lock-step rather than the three processes of `mission --realtime`: there the emulator
// keeps the wall clock (a ping not rendered in its window is dropped) and the agent, the
// emulator and the onboard consumer meet over loopback UDP and CAN, so when a pose reaches the
// emulator and when a contact reaches the agent depend on the scheduler: two runs of one seed
// differed by hundreds of dropped pings and by whole targets (issue 24). No real-time client is
// in this loop, so nothing needs the wall clock; the real-time loop stays for what needs it
// (a vehicle computer or other software on the wire).
//
// One batch of `batch_s` mission seconds at a time:
//   1. the contacts the onboard consumer reported during the previous batch reach the agent
//      (a fixed, deterministic latency of at most one batch on top of the consumer's own:
//      its reorder window and the detector's settle distance, as on the wire);
//   2. the agent steps to each ping time of the batch (autonomy/agent.h); each ping is flown
//      from the agent's state there: position, depth, heading, pitch (the pose a vehicle would
//      send with `run --pose-from udp:`), the seabed depth for altitude keeping from the
//      scene's large-scale relief (what the emulator's altimeter publishes);
//   3. the batch's pings are rendered in parallel (`threads`), each from (seed, ping number)
//      only (sim/render/ping_renderer.h), and encoded as the emulator encodes them: XTF, with
//      the navigation the scenario's navigation sensor model measures (emulator/xtf_ping.h);
//   4. the packets are fed to the onboard consumer in order (atr/onboard_pipeline.h), exactly
//      the bytes `run --udp` would send.
// The loop ends `drain_s` of mission time after the agent's plan is done (the last contacts
// may still ask for re-looks), at `max_duration_s`, or when stop_requested() turns true.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "atr/contact.h"
#include "atr/onboard_pipeline.h"
#include "atr/subspace_classifier.h"
#include "autonomy/agent.h"
#include "sim/render/ping_renderer.h"
#include "sim/scenario.h"
#include "sim/scene/scene.h"
#include "study/survey_score.h"

namespace sonarloop::mission {

struct LockstepOptions {
  int threads = 1;        // render threads, >= 1
  double batch_s = 0.5;   // mission seconds per batch, > 0
  double drain_s = 20.0;  // mission seconds after the plan is done, >= 0
  double max_duration_s = 1e7;
  render::RendererKind renderer = render::RendererKind::kProfile;
  // Throws std::invalid_argument naming the first value out of range.
  void validate() const;
};

struct LockstepHooks {
  // Polled once per batch; true ends the mission early (LockstepResult::stopped).
  std::function<bool()> stop_requested;
  // After each batch (progress).
  std::function<void(const autonomy::Agent&)> on_batch;
  // Every contact as the onboard consumer reports it.
  std::function<void(const atr::Contact&)> on_contact;
  // Every candidate of its detector as its fate is decided, with the waterfall that still holds
  // its pings (training chips: mission/survey_chips.h).
  std::function<void(const atr::Waterfall&, const atr::CandidateReport&)> on_candidate;
  // The stream's bytes in order: the XTF file header first, then each ping's packet (recording).
  std::function<void(std::span<const std::uint8_t>)> on_packet;
};

struct LockstepResult {
  std::vector<atr::Contact> contacts;            // the onboard consumer's, in the order reported
  std::vector<atr::CandidateReport> candidates;  // every candidate of its detector
  std::vector<study::SwathPing> pings;           // every ping flown (true pose; coverage)
  atr::OnboardStats onboard;
  double mission_s = 0.0;
  bool stopped = false;  // by stop_requested()
};

// Flies `agent` (constructed by the caller with its plan and start; read it afterwards for its
// objects and re-looks) over `scene` (built from scenario.scene) with the onboard consumer of
// `model` (none: contacts unclassified). The onboard options' frame_origin is set to the scenario's
// origin. Throws std::invalid_argument for bad options.
LockstepResult run_lockstep(const Scenario& scenario, const scene::Scene& scene,
                            std::optional<atr::Model> model, const atr::OnboardOptions& onboard,
                            autonomy::Agent& agent, const LockstepOptions& options,
                            const LockstepHooks& hooks = {});

}  // namespace sonarloop::mission
