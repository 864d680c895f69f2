#include "ranks/sweep_ranks.h"

#include <utility>

#include "ranks/chip_ranks.h"

namespace sonarloop::ranks {

namespace {

// Every chip set of every render group at every slot, in study::group_chip_sets' order (rank
// 0's); false when one came back short (rank 0 stopped).
bool serve_experiment(const study::SweepExperiment& e, const study::SweepSettings& settings,
                      int threads, const std::function<bool()>& stop) {
  for (const study::RenderGroup& g : study::render_groups(e)) {
    const std::vector<study::ChipSet> sets = study::group_chip_sets(e, g, settings);
    for (int slot = 0; slot < static_cast<int>(g.resolutions_m.size()); ++slot) {
      for (const study::ChipSet& s : sets) {
        if (render_sweep_chips(*s.renderer, slot, s.count, threads, {}, stop) < s.count) {
          return false;
        }
      }
    }
  }
  return true;
}

}  // namespace

std::size_t render_sweep_chips(const render::ChipRenderer& r, int slot, std::size_t count,
                               int threads,
                               const std::function<void(const render::ChipImage&)>& sink,
                               const std::function<bool()>& stop) {
  std::vector<render::ChipJob> jobs(count);
  for (std::size_t i = 0; i < count; ++i)
    jobs[i] = render::ChipJob{i, slot};
  return render_chips_on_ranks(r, jobs, threads, sink, stop);
}

bool serve_sweep(const std::vector<study::SweepExperiment>& experiments,
                 const study::SweepSettings& settings, int threads,
                 const std::function<bool()>& stop) {
  for (const study::SweepExperiment& e : experiments) {
    if (!serve_experiment(e, settings, threads, stop)) return false;
  }
  return true;
}

}  // namespace sonarloop::ranks
