#include "sim/render/track_renderer.h"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace sonarloop::render {

void render_track(const scene::Scene& scene, const PingRenderer& renderer,
                  std::span<const Pose> poses, std::uint64_t seed,
                  const TrackRenderOptions& options, const PingSink& sink,
                  const std::function<void(double)>& on_progress) {
  const int threads = std::max(1, options.threads);
  std::vector<PingScratch> scratch(static_cast<std::size_t>(threads));
  std::vector<PingLines> lines;
  std::vector<std::vector<TargetTrace>> traces;
  std::size_t begin = 0;
  while (begin < poses.size()) {
    // the chunk: consecutive pings near the first one
    std::size_t end = begin + 1;
    const Vec2 start = poses[begin].position_W.head<2>();
    while (end < poses.size() &&
           (poses[end].position_W.head<2>() - start).norm() <= options.chunk_length_m) {
      ++end;
    }
    scene::Box2 region = renderer.swath_region(poses[begin]);
    for (std::size_t k = begin + 1; k < end; ++k) {
      const scene::Box2 r = renderer.swath_region(poses[k]);
      region.min = region.min.cwiseMin(r.min);
      region.max = region.max.cwiseMax(r.max);
    }
    const auto view = scene.view(region, threads);
    const std::size_t n = end - begin;
    lines.resize(n);
    traces.resize(n);
    std::atomic<std::size_t> next{0};
    auto work = [&](std::size_t worker) {
      for (std::size_t k = next++; k < n; k = next++) {
        renderer.render(*view, poses[begin + k], seed, options.first_ping_index + begin + k,
                        options.ping, scratch[worker], lines[k]);
        traces[k] = scratch[worker].traces;
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t)
      pool.emplace_back(work, static_cast<std::size_t>(t));
    work(0);
    for (auto& th : pool)
      th.join();
    for (std::size_t k = 0; k < n; ++k)
      sink(begin + k, lines[k], traces[k]);
    begin = end;
    if (on_progress) on_progress(static_cast<double>(begin) / static_cast<double>(poses.size()));
  }
}

}  // namespace sonarloop::render
