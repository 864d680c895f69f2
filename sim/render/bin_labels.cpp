#include "sim/render/bin_labels.h"

#include <algorithm>

namespace sonarloop::render {

void start_bin_labels(const RenderOptions& options, int bins, BinLabelScratch& s) {
  if (!options.labels) return;
  const auto nb = static_cast<std::size_t>(bins);
  for (int side = 0; side < 2; ++side) {
    s.target_energy[side].assign(nb, 0.0);
    s.seabed_seen[side].assign(nb, 0);
    s.seabed_hidden[side].assign(nb, 0);
  }
}

void finish_bin_labels(const RenderOptions& options, int bins, int k0, int k1, int blur,
                       const std::vector<double> (&energy)[2], const BinLabelScratch& s,
                       PingLines& out) {
  if (!options.labels) {
    out.port_label.clear();
    out.stbd_label.clear();
    return;
  }
  const auto nb = static_cast<std::size_t>(bins);
  for (int side = 0; side < 2; ++side) {
    auto& label = side == 0 ? out.port_label : out.stbd_label;
    label.assign(nb, kLabelSeabed);
    if (!(options.side_mask & (1 << side))) continue;
    const auto& total = energy[side];
    const auto& target = s.target_energy[side];
    const auto& seen = s.seabed_seen[side];
    const auto& hidden = s.seabed_hidden[side];
    if (total.size() < nb || target.size() < nb) continue;
    for (int k = std::max(0, k0); k < std::min(k1, bins); ++k) {
      // the pulse window the line's blur averages over: the bin and blur - 1 bins before it
      double e_total = 0.0, e_target = 0.0;
      std::uint64_t n_seen = 0, n_hidden = 0;
      for (int j = std::max(0, k - blur + 1); j <= k; ++j) {
        const auto u = static_cast<std::size_t>(j);
        e_total += total[u];
        e_target += target[u];
        n_seen += seen[u];
        n_hidden += hidden[u];
      }
      const auto u = static_cast<std::size_t>(k);
      if (e_target > 0.0 && e_target > kHighlightShare * e_total) {
        label[u] = kLabelHighlight;
      } else if (n_hidden > n_seen) {
        label[u] = kLabelShadow;
      }
    }
  }
}

}  // namespace sonarloop::render
