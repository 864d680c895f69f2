#pragma once
// `sonarloop bench` accuracy sections: renders of the same pings compared with a high-fidelity
// ray-traced reference (no speckle, no noise, so that only the geometry and the shading differ).
//
//   fidelity   one scenario, pings across each target: every fidelity setting of both
//              renderers (ms per ping, RMS dB error, target shadow-edge error) for the
//              speed-against-accuracy chart (tools/plot_bench.py)
//   accuracy   each renderer at its default setting against the reference, over the default
//              scenario and the four seabed kinds with every sonar preset, and a terrain-following
//              line with pitch and roll over the rocky seabed
//
// Errors (compare_lines):
//   rms_db_error            RMS of 10·log10(I / I_ref) over bins lit in both renders, within
//                           kRmsFloorDb of the reference line's median lit level (bins far
//                           below it, slivers of seabed lit at the edge of a shadow, are
//                           below any recorder's range, and their ratio of two near-zero
//                           energies swings by dB for a micrometre of height)
//   shadow_edge_error_bins  mean |far edge of a target's shadow − the reference's| (truth traces)
//   terrain_edge_error_bins mean distance from each lit/dark transition of the line (beyond the
//                           nadir gap, before the reference's last lit bin) to the nearest one
//                           in the reference, both ways, edges more than kMaxEdgeMatchBins
//                           apart counted as that many

#include <functional>
#include <string>
#include <vector>

#include "config/loader/scenario_loader.h"
#include "drivers/json/json_writer.h"
#include "sim/render/ping_renderer.h"

namespace sonarloop::bench {

// Where a section's results and progress go (`sonarloop bench`: JSON lines on stdout, a
// progress bar on stderr).
struct SectionOutput {
  std::function<void(const json::Writer&)> emit;  // one JSON object per result
  // (label, steps done, steps in all): before the first step with 0, then after each
  std::function<void(const std::string& label, double done, double total)> progress;
};

inline constexpr int kMaxEdgeMatchBins = 10;
inline constexpr double kRmsFloorDb = 60.0;

// The sonar with what its recorder adds to every ping whatever the scene (the transmit ring-down)
// taken out: the bench compares echoes, and bins that read full scale in both lines would dilute
// the errors and count as edges. (The noise floor goes with RenderOptions::noise, off here.)
render::SonarDesc echoes_only(render::SonarDesc sd);

// `base` made an isotropic-pixel strip sonar (the paper's): range bin, along-track resolution and
// range resolution all pixel_m, out to range_m; echoes_only.
render::SonarDesc isotropic_strip_sonar(const render::SonarDesc& base, double range_m,
                                        double pixel_m);

struct LineSet {
  std::vector<render::PingLines> lines;
  std::vector<std::vector<render::TargetTrace>> traces;
  double seconds = 0.0;  // rendering only (one thread)
};

// Renders `poses` without speckle or noise, with truth traces, on one thread (after one untimed
// pass that makes the tiles or views).
LineSet render_set(const scene::Scene& scene, const render::PingRenderer& renderer,
                   const std::vector<Pose>& poses);
// The same lines on `threads` threads, each ping on one (the reference's renders, whose time
// is not reported: the lines are those of render_set, ping for ping).
LineSet render_reference(const scene::Scene& scene, const render::PingRenderer& renderer,
                         const std::vector<Pose>& poses, int threads);

struct LineErrors {
  double rms_db = 0.0;
  long lit_bins = 0;
  double target_edge_bins = 0.0;
  long target_edges = 0;
  double terrain_edge_bins = 0.0;
  long terrain_edges = 0;
};
LineErrors compare_lines(const LineSet& got, const LineSet& ref);

// The sections; each prints JSON lines. full: the exhaustive grid and an 8x8-ray reference
// (else 4x4 and a compact grid). The reference renders on `threads` threads; the timed renders
// on one.
void bench_fidelity(const config::Scenario& s, bool full, int threads, const SectionOutput& out);
void bench_accuracy(const config::Scenario& s, bool full, int threads, const SectionOutput& out);

}  // namespace sonarloop::bench
