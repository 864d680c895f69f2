#include "sim/render/ping_renderer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>

#include "sim/render/echo_model.h"
#include "sim/render/profile_renderer.h"
#include "sim/render/raytrace_renderer.h"

namespace sonarloop::render {

RendererScratch::~RendererScratch() = default;

PingScratch::PingScratch() = default;
PingScratch::~PingScratch() = default;
PingScratch::PingScratch(PingScratch&&) noexcept = default;
PingScratch& PingScratch::operator=(PingScratch&&) noexcept = default;

const char* renderer_name(RendererKind kind) {
  return kind == RendererKind::kRaytrace ? "raytrace" : "profile";
}

std::optional<RendererKind> parse_renderer(const std::string& name) {
  if (name == "profile") return RendererKind::kProfile;
  if (name == "raytrace") return RendererKind::kRaytrace;
  return std::nullopt;
}

Fidelity default_fidelity(const SonarSetup& s) {
  Fidelity f;
  f.rays_per_bin = s.desc.rays_per_bin > 0 ? s.desc.rays_per_bin : 2;
  if (s.desc.along_track_rays > 0) {
    f.along_track_rays = s.desc.along_track_rays;
  } else if (s.desc.along_track == AlongTrackModel::kStrip) {
    f.along_track_rays = 2;
  } else {
    // two rays per bin size across the beam's footprint at maximum range
    const double footprint = s.desc.max_range_m * s.horizontal_beamwidth_rad;
    f.along_track_rays =
        std::clamp(static_cast<int>(std::ceil(2.0 * footprint / s.desc.bin_size_m)), 2, 32);
  }
  // enough for the pixel and no more: a heightfield no coarser than half a bin, marched at half
  // its spacing
  f.heightfield_spacing_m = 0.5 * s.desc.bin_size_m;
  f.march_step_per_spacing = 0.5;
  return f;
}

MarchPlan march_plan(const Fidelity& f, double grid_spacing_m, double bin_size_m) {
  MarchPlan p;
  // the coarsest level whose spacing is at most the fidelity's (level 0 if the grid is coarser)
  while (p.level < seabed::kMaxSeabedLevel && grid_spacing_m * static_cast<double>(2 << p.level) <=
                                                  f.heightfield_spacing_m * (1.0 + 1e-9)) {
    ++p.level;
  }
  p.spacing_m = grid_spacing_m * static_cast<double>(1 << p.level);
  const double fraction = f.march_step_per_spacing > 0.0 ? f.march_step_per_spacing : 0.5;
  p.step_m = std::min(fraction * p.spacing_m, 0.5 * bin_size_m);
  return p;
}

PingRenderer::PingRenderer(const SonarSetup& sonar, const Fidelity& fidelity)
    : sonar_(sonar), fidelity_(fidelity), echo_(std::make_unique<EchoModel>(sonar, fidelity)) {}

PingRenderer::~PingRenderer() = default;

scene::Box2 PingRenderer::swath_region(const Pose& pose) const {
  const double r = sonar_.desc.max_range_m;
  const Vec2 c = pose.position_W.head<2>();
  return scene::Box2{c - Vec2(r, r), c + Vec2(r, r)};
}

std::unique_ptr<PingRenderer> make_ping_renderer(RendererKind kind, const SonarSetup& sonar,
                                                 std::optional<Fidelity> fidelity) {
  const Fidelity f = fidelity.value_or(default_fidelity(sonar));
  if (kind == RendererKind::kRaytrace) return std::make_unique<RaytraceRenderer>(sonar, f);
  return std::make_unique<ProfileRenderer>(sonar, f);
}

}  // namespace sonarloop::render
