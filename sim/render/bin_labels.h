#pragma once
// Per-bin labels of a ping, for training detection and segmentation learners
// (RenderOptions::labels): each slant-range bin of each side is seabed, target highlight or
// target shadow (kLabel* in ping_renderer.h), decided from the physics of the render itself, not
// from a box drawn around the target.
//
// The renderers add, besides the echo energy of each bin:
//   - the share of it that target echoes bring (the same tubes, splatted the same way);
//   - the seabed samples (profile: march samples above the running horizon; raytrace: rays)
//     that land in the bin, as seen or as hidden by a target: a sample is hidden when a target
//     hit nearer than it lies on its ray (profile: inside the tube of a target ray that hit
//     nearer, where the target "wins and raises the horizon"; raytrace: the seabed a target ray
//     reaches when continued through the target, or the target's base where that lies on the
//     seabed). Seabed in the terrain's own shadow is neither.
// The rule, per bin, over the same pulse window as the line's blur (echo_model.h: the bin and
// the blur - 1 bins before it; one bin when the pulse is a bin long), before noise and speckle:
//   highlight  target echo energy > kHighlightShare x the bin's whole echo energy;
//   shadow     otherwise, if more seabed samples are hidden by a target than seen;
//   seabed     otherwise (including the water column and bins with no echo at all).
// Outside the rendered range window every bin is seabed. Costs nothing unless asked for: the
// accumulators are neither sized nor touched when RenderOptions::labels is off.
#include <cstdint>

#include "sim/render/ping_renderer.h"

namespace sonarloop::render {

// Target echoes must bring more than this share of a bin's echo energy for a highlight.
inline constexpr double kHighlightShare = 0.5;

// Sizes and zeroes the accumulators for `bins` bins per side when options.labels is set.
void start_bin_labels(const RenderOptions& options, int bins, BinLabelScratch& s);

// One seabed sample (or ray) of `side` landing in `bin`: seen by the ping or hidden by a target.
inline void count_seabed_sample(BinLabelScratch& s, int side, int bin, bool hidden) {
  auto& v = hidden ? s.seabed_hidden[side] : s.seabed_seen[side];
  if (bin >= 0 && static_cast<std::size_t>(bin) < v.size()) ++v[static_cast<std::size_t>(bin)];
}

// Writes out.port_label / stbd_label (bins each) from `energy` (per side: the accumulated echo,
// before noise, blur and speckle) and the label accumulators, over bins [k0, k1) with a pulse of
// `blur` bins; clears them when options.labels is off.
void finish_bin_labels(const RenderOptions& options, int bins, int k0, int k1, int blur,
                       const std::vector<double> (&energy)[2], const BinLabelScratch& s,
                       PingLines& out);

}  // namespace sonarloop::render
