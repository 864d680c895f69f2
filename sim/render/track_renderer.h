#pragma once
// Rendering a sequence of pings (a straight survey line, a dataset's few pings): builds Embree
// views over chunks of consecutive pings, so that only the swath the pings can see is ever
// generated and compiled, and renders each chunk's pings on several threads. Every ping is a
// pure function of (scene, sonar, pose, seed, ping index), so the output does not depend on the
// number of threads.
#include <cstdint>
#include <functional>
#include <span>

#include "sim/render/ping_renderer.h"

namespace sonarloop::render {

struct TrackRenderOptions {
  RenderOptions ping;  // per-ping options (truth, range window, ...)
  int threads = 1;
  double chunk_length_m = 20.0;  // pings whose positions lie within this of a chunk's first ping
                                 // share one scene view
  std::uint64_t first_ping_index = 0;  // ping index of poses[0] (randomness key)
};

// Called for every ping in order, on the calling thread: (index into poses, lines, traces).
using PingSink = std::function<void(std::size_t, const PingLines&, std::span<const TargetTrace>)>;

void render_track(const scene::Scene& scene, const PingRenderer& renderer,
                  std::span<const Pose> poses, std::uint64_t seed,
                  const TrackRenderOptions& options, const PingSink& sink,
                  const std::function<void(double)>& on_progress = {});

}  // namespace sonarloop::render
