#pragma once
// The ray-traced reference renderer (Pailhas et al. 2010, Sec. 2.3: pseudo ray tracing plus the
// energetic sonar equation). For one ping it fans rays from the transducer across the vertical
// plane of each side and across the along-track beam (ray_fan.h), intersects them with one Embree
// scene of the seabed grid and the targets (scene::SceneView), and adds each hit's echo to the
// range bin of its slant range (echo_model.h). A ray's echo is spread over the slant ranges its
// tube spans on the surface it hits, Δr = r·dδ·tan θ, so a slope facing away from the sonar stays
// lit rather than dropping bins between rays. Shadows fall out of visibility: a ray stopped by
// a target never reaches the seabed behind it.
//
// It models more than a heightfield seabed needs (a BVH of millions of triangles, ~7,000 rays
// per ping) and is kept as the reference the profile renderer is measured against, and for
// scenes a heightfield cannot represent (docs/rendering.md).
//
// Views: the renderer keeps the Embree views it built (a few, least recently used first out;
// shared with other renderers by share_views_with),
// keyed by scene and region. A ping's view covers RenderOptions::view_region if given, else the
// ground the ping can reach snapped outwards to a kViewGrid_m grid, so that the view a ping is
// rendered with depends only on the ping: output is byte-identical whatever was rendered
// before. A view is built on the thread that first needs it (others needing it wait) with
// view_build_threads threads.
#include <cstddef>
#include <future>
#include <memory>
#include <mutex>
#include <vector>

#include "sim/render/ping_renderer.h"

namespace sonarloop::render {

// Grid to which default view regions are snapped (metres).
inline constexpr double kViewGrid_m = 32.0;

class RaytraceRenderer final : public PingRenderer {
 public:
  RaytraceRenderer(const SonarSetup& sonar, const Fidelity& fidelity);
  ~RaytraceRenderer() override;

  RendererKind kind() const override { return RendererKind::kRaytrace; }
  void render(const scene::Scene& scene, const Pose& pose, std::uint64_t seed,
              std::uint64_t ping_index, const RenderOptions& options, PingScratch& scratch,
              PingLines& out) const override;
  void prepare(const scene::Scene& scene, const Pose& pose, const RenderOptions& options,
               PingScratch& scratch) const override;

  // Threads that build a view (tiles and BVH); default: all hardware threads.
  void set_view_build_threads(int threads) { build_threads_ = threads < 1 ? 1 : threads; }
  // Keeps its views with `other`'s from now on: a view depends only on the scene and the region,
  // so renderers of different fidelity or sonar over one scene (a bench's reference and the
  // renderer it measures) build each view once. Call before rendering.
  void share_views_with(const RaytraceRenderer& other) { views_ = other.views_; }

  // The view the ping from `pose` is rendered with (built now if needed).
  std::shared_ptr<const scene::SceneView> view_for(const scene::Scene& scene, const Pose& pose,
                                                   const RenderOptions& options) const;
  // The region of that view (before clipping to the seabed).
  scene::Box2 view_region_for(const Pose& pose, const RenderOptions& options) const;

  // The three phases of render(), public so that `sonarloop bench` can time Embree alone on
  // exactly the renderer's rays: generate_rays fills scratch.rays/meta (returns the nadir
  // altitude, NaN if the sonar is out of the water), intersect traces them (Embree only, in
  // batches; false when options.abandon stopped it), and shade turns hits into intensity per
  // bin and finishes the lines.
  double generate_rays(const scene::Scene& scene, const scene::SceneView& view, const Pose& pose,
                       const RenderOptions& options, PingScratch& scratch) const;
  static bool intersect(const scene::SceneView& view, const RenderOptions& options,
                        PingScratch& scratch);
  // The bench's baseline on the same rays: copy_rays keeps a copy of the generated rays aside
  // (into `to`'s ray buffer), intersect_one_by_one traces a scratch's rays with one rtcIntersect1
  // each and nothing else (no packet, no context flags), ray_count says how many there are.
  static void copy_rays(const PingScratch& from, PingScratch& to);
  static void intersect_one_by_one(const scene::SceneView& view, PingScratch& scratch);
  static std::size_t ray_count(const PingScratch& scratch);
  void shade(const scene::Scene& scene, const scene::SceneView& view, std::uint64_t seed,
             std::uint64_t ping_index, const RenderOptions& options, double altitude,
             PingScratch& scratch, PingLines& out) const;

 private:
  std::shared_ptr<const scene::SceneView> get_view(const scene::Scene& scene,
                                                   const scene::Box2& region) const;

  struct ViewEntry {
    std::uint64_t scene_uid = 0;
    scene::Box2 region;
    std::shared_future<std::shared_ptr<const scene::SceneView>> view;
    std::uint64_t last_use = 0;
  };
  static constexpr std::size_t kMaxViews = 4;
  struct ViewStore {
    std::mutex mu;
    std::vector<ViewEntry> entries;
    std::uint64_t use_clock = 0;
  };
  int build_threads_;
  std::shared_ptr<ViewStore> views_ = std::make_shared<ViewStore>();
};

}  // namespace sonarloop::render
