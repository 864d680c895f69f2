#pragma once
// The heightfield profile renderer (the default; ping_renderer.h): the seabed is a heightfield,
// so it is marched, not ray traced.
//
// Profile march. Each along-track sample j of the ping (a strip offset, or an angle ψ across a
// real beam: echo_model.h) has a beam plane through the transducer, perpendicular to the
// vehicle's x axis (a cone sin ψ = const for a beam sample), tilted with pitch; roll only turns
// the vertical beam pattern. The plane cuts the heightfield along a ground line. In the plane,
// with u the horizontal direction across track (to the side) and w the in-plane direction below
// it, a point is (s, β): s its horizontal distance across track, β its depth below the sonar
// along w. The line is marched outwards from nadir (or from RenderOptions::shadow_margin_m
// before the range window) at a step no coarser than half the heightfield spacing or half a
// range bin (march_plan()), reading heights with the scene's bilinear interpolation straight
// from the heightmap tiles (seabed/height_sampler.h): no seabed BVH.
//
// Visibility is a running horizon (the terrain line-of-sight sweep of "voxel space" renderers):
// a sample is lit only if its depression tan φ = β/s is not larger than the smallest tan φ of
// every nearer sample, so shadows cost O(samples). Each segment between consecutive samples is
// lit where it lies at or above the horizon ray β = m·s (m the running minimum): a linear test,
// so a segment that passes into or out of a shadow is clipped exactly where it crosses the
// horizon. Each lit (part of a) segment deposits its echo, spread uniformly over the slant ranges
// it spans, with the sonar equation of echo_model.h: it subtends dφ = |P0 × P1| / (|P0| |P1|)
// seen from the transducer, its incidence comes from the heightfield normal (the gradient of the
// bilinear surface, averaged over the segment), its sediment from the nearest lattice point.
//
// Targets. Each target's bounding sphere is projected into each beam plane; where a plane meets
// it, only the part of the plane's ray fan (ray_fan.h, the same rays the ray tracer would cast)
// whose depressions the sphere covers is cast at a BVH of the targets alone
// (scene/target_bvh.h). A target hit counts only where no seabed nearer to the sonar rises above
// its ray (the running horizon at the hit); its echo is the ray tracer's (Lambert facet, ray
// tube). The seabed behind a target is hidden where it lies inside the tube of a ray that hit the
// target nearer than it: the target raises the horizon, so its shadow falls behind it (and a
// gap under a raised target stays lit). Planes that meet no target cast no rays at all.
//
// What it cannot represent (use the raytrace renderer): overhangs and caves in the seabed
// (a heightfield has one height per point), and seabed seen through a gap in the targets'
// bounding spheres' depression range is exact only to the ray spacing.
#include "sim/render/ping_renderer.h"

namespace sonarloop::render {

class ProfileRenderer final : public PingRenderer {
 public:
  ProfileRenderer(const SonarSetup& sonar, const Fidelity& fidelity);

  RendererKind kind() const override { return RendererKind::kProfile; }
  void render(const scene::Scene& scene, const Pose& pose, std::uint64_t seed,
              std::uint64_t ping_index, const RenderOptions& options, PingScratch& scratch,
              PingLines& out) const override;
  void prepare(const scene::Scene& scene, const Pose& pose, const RenderOptions& options,
               PingScratch& scratch) const override;

  // A seabed below the nadir depth by more than this is assumed not to reach into the range
  // window from nearer ground than shadow_margin_m allows for (chips: where the march starts).
  static constexpr double kSeabedSlack_m = 1.0;

 private:
  struct Line;
  class LineMarch;  // the passes of one line's march (profile_line_march.cpp)
  void march(const scene::Scene& scene, const Line& line, const RenderOptions& options,
             PingScratch& scratch) const;
  void cast_target_rays(const scene::Scene& scene, const Line& line, PingScratch& scratch) const;
};

}  // namespace sonarloop::render
