#pragma once
// Rendering a sequence of pings (a straight survey line, a bench's image): renders the pings on
// several threads in blocks of consecutive pings and hands them to a sink in order. Each worker
// prepares the ping a few ahead of the one it renders (PingRenderer::prepare: heightmap tiles, or
// the ray tracer's view), so that the scene is made ahead of the pings that read it. Every ping
// is a pure function of (scene, sonar, pose, seed, ping index), so the output does not depend on
// the number of threads.
#include <cstdint>
#include <functional>
#include <span>

#include "sim/render/ping_renderer.h"

namespace sonarloop::render {

struct TrackRenderOptions {
  RenderOptions ping;  // per-ping options (truth, range window, ...)
  int threads = 1;
  std::size_t block_pings = 64;        // pings rendered between two hand-overs to the sink
  std::uint64_t first_ping_index = 0;  // ping index of poses[0] (randomness key)
};

// Called for every ping in order, on the calling thread: (index into poses, lines, traces).
using PingSink = std::function<void(std::size_t, const PingLines&, std::span<const TargetTrace>)>;

void render_track(const scene::Scene& scene, const PingRenderer& renderer,
                  std::span<const Pose> poses, std::uint64_t seed,
                  const TrackRenderOptions& options, const PingSink& sink,
                  const std::function<void(double)>& on_progress = {});

}  // namespace sonarloop::render
