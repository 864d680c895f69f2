#include "sim/render/track_renderer.h"

#include <algorithm>
#include <vector>

#include "common/parallel_for.h"

namespace sonarloop::render {

void render_track(const scene::Scene& scene, const PingRenderer& renderer,
                  std::span<const Pose> poses, std::uint64_t seed,
                  const TrackRenderOptions& options, const PingSink& sink,
                  const std::function<void(double)>& on_progress) {
  const int threads = std::max(1, options.threads);
  const std::size_t block = std::max<std::size_t>(1, options.block_pings);
  // a worker prepares the ping this far ahead of the one it renders
  const std::size_t ahead = 4 * static_cast<std::size_t>(threads);
  std::vector<PingScratch> scratch(static_cast<std::size_t>(threads));
  std::vector<PingLines> lines(block);
  std::vector<std::vector<TargetTrace>> traces(block);
  for (std::size_t begin = 0; begin < poses.size(); begin += block) {
    const std::size_t n = std::min(block, poses.size() - begin);
    parallel_for(n, threads, [&](std::size_t k, int worker) {
      PingScratch& s = scratch[static_cast<std::size_t>(worker)];
      const std::size_t p = begin + k;
      if (p + ahead < poses.size()) renderer.prepare(scene, poses[p + ahead], options.ping, s);
      renderer.render(scene, poses[p], seed, options.first_ping_index + p, options.ping, s,
                      lines[k]);
      traces[k] = s.traces;
    });
    for (std::size_t k = 0; k < n; ++k)
      sink(begin + k, lines[k], traces[k]);
    if (on_progress)
      on_progress(static_cast<double>(begin + n) / static_cast<double>(poses.size()));
  }
}

}  // namespace sonarloop::render
