#pragma once
// `sonarloop render`'s target truth (tools/cmd_render.cpp renders the line): where each target
// shows in the rendered pings, gathered ping by ping from the renderer's traces (the pings and
// samples of its highlight and shadow, the highlight's energy centroid), and truth.json, which
// states it with the line's geometry and the indexing conventions.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "sim/frames.h"
#include "sim/render/ping_renderer.h"
#include "sim/scene/scene.h"

namespace sonarloop::products {

// One target's extent in the line, in pings and samples of its side (-1: not seen).
struct TargetTruth {
  int side = -1;
  int ping_first = -1, ping_last = -1;
  int sample_first = -1, sample_last = -1;
  int shadow_ping_first = -1, shadow_ping_last = -1;
  int shadow_first = -1, shadow_last = -1;
  double energy = 0.0, energy_ping = 0.0, energy_sample = 0.0;  // for the energy centroid
};

// Adds ping k's traces to the truth of their targets (truth is indexed by PlacedTarget::index).
void add_ping_traces(std::vector<TargetTruth>& truth, std::size_t k,
                     std::span<const render::TargetTrace> traces);

// The rendered line, as truth.json describes it.
struct RenderedLine {
  std::string scenario;
  std::uint64_t seed = 0;
  double latitude_deg = 0.0, longitude_deg = 0.0;  // the scenario origin
  std::string sonar;
  std::size_t pings = 0;
  int bins_per_side = 0;
  double bin_size_m = 0.0, ping_spacing_m = 0.0, altitude_m = 0.0;
  Vec2 track_start = Vec2::Zero(), track_end = Vec2::Zero();  // [north, east] m
  std::string renderer;
  double render_s = 0.0;
  int threads = 1;
};

// Writes truth.json: the line and each target of the scene with its truth.
void write_render_truth_json(const std::string& path, const RenderedLine& line,
                             const scene::Scene& sc, const std::vector<TargetTruth>& truth);

}  // namespace sonarloop::products
