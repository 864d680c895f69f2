#pragma once
// The ping renderer (Pailhas et al. 2010, Sec. 2.3): pseudo ray tracing plus the energetic sonar
// equation. For one ping it fans rays from the transducer across the vertical plane of each side
// and across the along-track beam, intersects them with the scene (Embree), and adds each hit's
// echo intensity to the range bin of its slant range:
//
//   I = SL · G(ψ, δ) · σ · dA / r⁴ · 10^(-2αr/10)      (linear form of SL − 2TL + TS + beam)
//
// with G the two-way beam pattern (acoustics/beam_pattern.h), σ the seabed's backscattering
// cross-section per unit area per steradian at the LOCAL grazing angle from the hit normal
// (APL-UW or Lambert, acoustics/backscatter_table.h) or a target facet's Lambert response
// μ·cos²θ with μ from its impedance (acoustics/target_scattering.h), and dA = r²·dΩ/cos θ the
// area a ray of solid angle dΩ illuminates. A ray's echo is spread over the slant ranges its
// tube spans on the surface it hits, Δr = r·dδ·tan θ (dδ its vertical width, θ the incidence),
// so a slope facing away from the sonar stays lit rather than dropping bins between rays.
// Shadows fall out of visibility: a ray stopped by a
// target never reaches the seabed behind it. Thermal noise (Mellen, in the receiver band, less
// the directivity index) is added, the line is blurred to the pulse's range resolution, and
// fully developed speckle multiplies each bin (exponential intensity).
//
// Ray fan. Rays are placed where a flat seabed at the measured nadir altitude a would put
// `rays_per_bin` of them in every range bin (depression δ = asin(a/r)), then tilted with the
// vehicle's roll and pitch so they stay in the sonar's beam plane. Each ray carries its own solid
// angle, so uneven terrain changes how many rays a bin gets but not the energy it receives.
// Default fidelity rule ("enough for the pixel size and no more"): rays 2 per bin in range and
// 2 per along-track resolution cell (strip) or per bin-size across the beam footprint at
// maximum range (beam, at most 32): about half a pixel apart on the ground in both directions.
//
// Allocation: none per ping; PingScratch holds every buffer, sized on first use.
#include <embree3/rtcore.h>

#include <cstdint>
#include <limits>
#include <vector>

#include "sim/frames.h"
#include "sim/render/sonar.h"
#include "sim/scene/scene.h"

namespace sonarloop::render {

// One ping: intensity per slant-range bin, bin k covering [k, k+1)·bin_size_m.
struct PingLines {
  std::vector<float> port;  // (bins) linear intensity re 1 µPa² at the receiver
  std::vector<float> stbd;
  double altitude_m = std::numeric_limits<double>::quiet_NaN();  // measured at nadir
};

// What a ping saw of each target, from the rays themselves (for truth files and tests).
struct TargetTrace {
  int target = -1;           // PlacedTarget::index
  int side = 0;              // 0 port, 1 starboard
  int highlight_first = -1;  // first and last bin with echoes from the target
  int highlight_last = -1;
  int shadow_first = -1;  // bins of seabed the target hides from the sonar
  int shadow_last = -1;
  double energy = 0.0;  // summed target echo intensity
};

struct RenderOptions {
  bool truth = false;        // fill PingScratch::traces (extra rays behind targets)
  bool speckle = true;       // AND-ed with SonarDesc::speckle
  bool noise = true;         // AND-ed with SonarDesc::noise
  double range_min_m = 0.0;  // only bins overlapping [range_min_m, range_max_m] are rendered
  double range_max_m = std::numeric_limits<double>::infinity();
  int side_mask = 3;  // bit 0 port, bit 1 starboard
};

// Per ray of a ping, what shading needs besides the Embree hit.
struct RayMeta {
  float solid_angle = 0.0f;       // dΩ (beam) or dδ·width (strip: divided by the hit range)
  float depression_width = 0.0f;  // dδ: the ray tube's width in the vertical plane (rad)
  float pattern = 0.0f;           // two-way vertical beam pattern (the horizontal one is in dΩ)
  std::uint8_t side = 0;          // 0 port, 1 starboard
};

struct PingScratch {
  std::vector<double> accum[2];
  std::vector<float> ray_edge;      // sin(world depression) at the vertical ray edges
  std::vector<float> along;         // along-track angle or offset per along ray
  std::vector<float> along_weight;  // along-track pattern × width
  std::vector<RTCRayHit> rays;      // the ping's rays (view-local coordinates), then their hits
  std::vector<RayMeta> meta;
  std::vector<TargetTrace> traces;
  std::uint64_t rays_cast = 0;  // rays intersected in the last ping (incl. truth rays)
};

struct Fidelity {
  int rays_per_bin = 2;
  int along_track_rays = 2;
};

class PingRenderer {
 public:
  PingRenderer(const scene::Scene& scene, const SonarSetup& sonar);

  const SonarSetup& sonar() const { return sonar_; }
  const Fidelity& fidelity() const { return fidelity_; }

  // Renders the ping emitted from `pose`. Randomness (speckle, noise) comes from
  // (seed, ping_index) only, so a ping is the same whichever thread renders it.
  // `view` must cover the swath (see swath_region()).
  void render(const scene::SceneView& view, const Pose& pose, std::uint64_t seed,
              std::uint64_t ping_index, const RenderOptions& options, PingScratch& scratch,
              PingLines& out) const;

  // The rectangle (north/east) a ping from `pose` can reach: max range around the sonar.
  scene::Box2 swath_region(const Pose& pose) const;

  // The three phases of render(), public so that `sonarloop bench` can time Embree alone on
  // exactly the renderer's rays: generate_rays fills scratch.rays/meta (returns the nadir
  // altitude, NaN if the sonar is out of the water), intersect traces them (Embree only), and
  // shade turns hits into intensity per bin and finishes the lines.
  double generate_rays(const scene::SceneView& view, const Pose& pose, const RenderOptions& options,
                       PingScratch& scratch) const;
  static void intersect(const scene::SceneView& view, PingScratch& scratch);
  void shade(const scene::SceneView& view, std::uint64_t seed, std::uint64_t ping_index,
             const RenderOptions& options, double altitude, PingScratch& scratch,
             PingLines& out) const;

 private:
  void generate_side(const scene::SceneView& view, const Pose& pose, int side, double altitude,
                     const RenderOptions& options, PingScratch& scratch) const;

  const scene::Scene& scene_;
  SonarSetup sonar_;
  Fidelity fidelity_;
  std::vector<acoustics::BackscatterTable> seabed_sigma_;  // per SedimentId
  std::vector<double> target_mu_;                          // per target index
  double source_level_lin_ = 0.0;
  double noise_lin_ = 0.0;  // mean noise intensity per bin
};

// The default fidelity rule (see the header comment), for a sonar and a seabed grid spacing.
Fidelity default_fidelity(const SonarSetup& sonar);

}  // namespace sonarloop::render
