#include "tools/sweep_ranks.h"

#include <utility>

#include "ranks/chip_ranks.h"
#include "tools/cli_helpers.h"

namespace sonarloop::tools {
using ranks::render_chips_on_ranks;

namespace {

// Renders every chip set of one slot in turn; false when one came back short (stopped).
bool serve_slot(std::initializer_list<std::pair<const render::ChipRenderer*, std::size_t>> sets,
                int slot, int threads) {
  for (const auto& s : sets) {
    if (render_sweep_chips(*s.first, slot, s.second, threads, {}) < s.second) return false;
  }
  return true;
}

bool serve_experiment(const study::SweepExperiment& e, const study::SweepSettings& settings,
                      int threads) {
  const std::size_t classes = e.classes.size();
  const std::size_t n_test = static_cast<std::size_t>(e.test_count) * classes;
  for (const study::RenderGroup& g : study::render_groups(e)) {
    const std::size_t n_train = static_cast<std::size_t>(g.train_count) * classes;
    const int slots = static_cast<int>(g.resolutions_m.size());
    if (study::is_fusion(e)) {
      const auto train = study::fusion_specs(e, g, settings, false);
      const auto test = study::fusion_specs(e, g, settings, true);
      const render::ChipRenderer rh(train.first), rs(train.second), th(test.first), ts(test.second);
      for (int slot = 0; slot < slots; ++slot) {
        if (!serve_slot({{&rh, n_train}, {&rs, n_train}, {&th, n_test}, {&ts, n_test}}, slot,
                        threads)) {
          return false;
        }
      }
      continue;
    }
    const render::ChipRenderer train_r(study::render_group_spec(e, g, settings, false));
    const render::ChipRenderer test_r(study::render_group_spec(e, g, settings, true));
    const auto look_r = study::other_look_renderers(e, g, settings);
    for (int slot = 0; slot < slots; ++slot) {
      if (!serve_slot({{&train_r, n_train}, {&test_r, n_test}}, slot, threads)) return false;
      for (const auto& r : look_r) {  // the test objects' other looks
        if (!serve_slot({{r.get(), n_test}}, slot, threads)) return false;
      }
    }
  }
  return true;
}

}  // namespace

std::size_t render_sweep_chips(const render::ChipRenderer& r, int slot, std::size_t count,
                               int threads,
                               const std::function<void(const render::ChipImage&)>& sink) {
  std::vector<render::ChipJob> jobs(count);
  for (std::size_t i = 0; i < count; ++i)
    jobs[i] = render::ChipJob{i, slot};
  return render_chips_on_ranks(r, jobs, threads, sink, [] { return stop_requested(); });
}

bool serve_sweep(const std::vector<study::SweepExperiment>& experiments,
                 const study::SweepSettings& settings, int threads) {
  install_stop_flag();
  for (const study::SweepExperiment& e : experiments) {
    if (!serve_experiment(e, settings, threads)) return false;
  }
  return true;
}

}  // namespace sonarloop::tools
