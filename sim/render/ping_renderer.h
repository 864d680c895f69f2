#pragma once
// The ping renderer interface (Pailhas et al. 2010, Sec. 2.3): (scene, sonar, pose, seed, ping
// index) -> one port and one starboard line of echo intensity per slant-range bin, from the
// energetic sonar equation
//
//   I = SL · G(ψ, δ) · σ · dA / r⁴ · 10^(-2αr/10)
//
// summed over every surface element the ping sees (echo_model.h has the shared terms). Two
// renderers implement it; both share every acoustic term, the along-track sampling, the ray fan
// laid out for the targets, the noise, the pulse blur and the speckle, and differ only in how they
// find what the ping sees:
//
//   profile   (profile_renderer.h, the default): the seabed is a heightfield, so each beam plane
//             cuts it along a ground line, marched outwards from nadir with a running horizon
//             (shadows in O(samples)); only the targets are ray traced (a small Embree BVH), and
//             only in the pings whose planes meet them.
//   raytrace  (raytrace_renderer.h, the reference): rays fanned across each beam plane are traced
//             through one Embree scene of the seabed grid and the targets.
//
// docs/rendering.md compares them (speed against accuracy) and says when to use which.
//
// Usage: make one renderer per sonar (make_ping_renderer), share it between threads (render() is
// const and thread-safe) and give each thread its own PingScratch. The same scene, sonar, pose,
// seed, ping index and options give byte-identical lines on any thread, in any order.
#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/frames.h"
#include "sim/render/sonar.h"
#include "sim/scene/embree_handles.h"
#include "sim/scene/scene.h"

namespace sonarloop::render {

enum class RendererKind { kProfile, kRaytrace };

const char* renderer_name(RendererKind kind);  // "profile", "raytrace"
// Parses "profile" or "raytrace"; nullopt otherwise.
std::optional<RendererKind> parse_renderer(const std::string& name);

// Per-bin labels (RenderOptions::labels; the rule is in bin_labels.h): values, not grey levels.
inline constexpr std::uint8_t kLabelSeabed = 0;     // seabed echo, water column, or nothing
inline constexpr std::uint8_t kLabelHighlight = 1;  // target echoes dominate the bin
inline constexpr std::uint8_t kLabelShadow = 2;     // most of the bin's seabed hidden by a target

// One ping: intensity per slant-range bin, bin k covering [k, k+1)·bin_size_m.
struct PingLines {
  std::vector<float> port;  // (bins) linear intensity re 1 µPa² at the receiver
  std::vector<float> stbd;
  double altitude_m = std::numeric_limits<double>::quiet_NaN();  // measured at nadir
  // (bins) kLabel* per bin when RenderOptions::labels is set; empty otherwise
  std::vector<std::uint8_t> port_label;
  std::vector<std::uint8_t> stbd_label;
};

// What a ping saw of each target (for truth files and tests).
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
  bool truth = false;        // fill PingScratch::traces
  bool labels = false;       // fill PingLines::port_label / stbd_label (bin_labels.h)
  bool speckle = true;       // AND-ed with SonarDesc::speckle
  bool noise = true;         // AND-ed with SonarDesc::noise
  double range_min_m = 0.0;  // only bins overlapping [range_min_m, range_max_m] are rendered
  double range_max_m = std::numeric_limits<double>::infinity();
  int side_mask = 3;  // bit 0 port, bit 1 starboard
  // Ground (horizontal distance) before the range window whose relief and targets can cast
  // shadows into it. Infinite (default): everything from nadir. A chip uses a few metres: the
  // profile renderer then marches only from there, the ray tracer's view starts there.
  double shadow_margin_m = std::numeric_limits<double>::infinity();
  // The sonar's height above the seabed straight below it, if the caller knows it (a chip's
  // geometry fixes it); NaN (default): measured (a ray or the heightmap below the sonar).
  double nadir_altitude_m = std::numeric_limits<double>::quiet_NaN();
  // raytrace only: the region (north/east) its Embree view covers. Pings given the same region
  // share one view; the region must hold the ground the ping reaches, and for byte-identical
  // output must depend only on the ping (not on what else was rendered). Default: the ground
  // the ping reaches, snapped outwards to a fixed grid (raytrace_renderer.h).
  std::optional<scene::Box2> view_region;
  // Set by another thread when the ping is no longer wanted (its send window has closed, or the
  // run stops): the renderer looks at it between beam planes (profile) or ray batches (ray
  // tracer) and returns at once, the lines unfinished; the caller discards them. Null: never.
  const std::atomic<bool>* abandon = nullptr;
};

// Whether the ping being rendered with `options` has been given up (RenderOptions::abandon).
inline bool abandoned(const RenderOptions& options) {
  return options.abandon && options.abandon->load(std::memory_order_relaxed);
}

// Per ray of a ping, what shading needs besides the Embree hit.
struct RayMeta {
  float solid_angle = 0.0f;       // dΩ (beam) or dδ·width (strip: divided by the hit range)
  float depression_width = 0.0f;  // dδ: the ray tube's width in the vertical plane (rad)
  float pattern = 0.0f;           // two-way vertical beam pattern (the horizontal one is in dΩ)
  std::uint8_t side = 0;          // 0 port, 1 starboard
};

// What the per-bin labels are made of (bin_labels.h), per side, per bin; sized only when
// RenderOptions::labels is set.
struct BinLabelScratch {
  std::vector<double> target_energy[2];       // the share of PingScratch::accum from target echoes
  std::vector<std::uint32_t> seabed_seen[2];  // seabed samples (rays) the ping sees
  std::vector<std::uint32_t> seabed_hidden[2];  // seabed samples a target hides from it
};

// A renderer's own per-thread buffers, besides the shared ones of PingScratch: one type per
// renderer (the profile renderer's is ProfileScratch, in profile_line.h; the ray tracer needs
// none), made by the renderer in the scratch it is given, on first use.
class RendererScratch {
 public:
  virtual ~RendererScratch();
};

// Buffers of one rendering thread, sized on first use (no allocation per ping afterwards): what
// both renderers use (the rays, their hits and what shading needs, the accumulated echoes, the
// truth and the labels), and the renderer's own (`own`). One PingScratch serves either
// renderer; given to another, it makes that one's own buffers anew.
// Made, moved and destroyed in ping_renderer.cpp, where Embree's RTCRayHit is complete (this
// header does not include Embree: sim/scene/embree_handles.h).
struct PingScratch {
  PingScratch();
  ~PingScratch();
  PingScratch(PingScratch&&) noexcept;
  PingScratch& operator=(PingScratch&&) noexcept;

  std::vector<double> accum[2];
  std::vector<double> raw_mean, raw_intensity;  // the receive chain's raw samples (echo_model.h)
  std::vector<float> ray_edge;                  // sin(world depression) at the vertical ray edges
  std::vector<RTCRayHit> rays;  // the ping's rays (view-local coordinates), then their hits
  std::vector<RayMeta> meta;
  std::vector<TargetTrace> traces;
  BinLabelScratch labels;
  std::uint64_t rays_cast = 0;           // rays intersected in the last ping (incl. truth rays)
  std::uint64_t samples = 0;             // profile: heightfield samples marched in the last ping
  std::unique_ptr<RendererScratch> own;  // the renderer's own buffers (made by it)

  // The renderer's own buffers as type T, made (replacing another renderer's) if need be.
  template <class T>
  T& own_as() {
    if (auto* p = dynamic_cast<T*>(own.get())) return *p;
    own = std::make_unique<T>();
    return static_cast<T&>(*own);
  }
};

// Fidelity knobs ("enough for the pixel size and no more", docs/rendering.md).
struct Fidelity {
  int rays_per_bin = 2;      // vertical rays per range bin (raytrace; profile: target rays)
  int along_track_rays = 2;  // beam planes (or rays) across the horizontal beam or strip
  // profile: read the coarsest heightfield level (spacing grid·2^L) whose spacing is at most
  // this (the scene's own grid if it is coarser already), and march at this fraction of that
  // level's spacing, never more than half a range bin
  double heightfield_spacing_m = 0.0;
  double march_step_per_spacing = 0.5;
};

// The default fidelity rule: two vertical rays per bin and two along-track samples per
// along-track resolution cell (strip) or per bin size across the beam's footprint at maximum
// range (beam, at most 32); the profile reads the coarsest heightfield level no coarser than
// half a bin and marches at half its spacing. SonarDesc::rays_per_bin and along_track_rays
// override the first two.
Fidelity default_fidelity(const SonarSetup& sonar);

// The heightfield level and march step the profile renderer uses with `fidelity` on a seabed
// whose finest grid is grid_spacing_m, for a sonar of bin_size_m.
struct MarchPlan {
  int level = 0;
  double spacing_m = 0.0;  // grid_spacing_m · 2^level
  double step_m = 0.0;
};
MarchPlan march_plan(const Fidelity& fidelity, double grid_spacing_m, double bin_size_m);

class EchoModel;

class PingRenderer {
 public:
  virtual ~PingRenderer();
  PingRenderer(const PingRenderer&) = delete;
  PingRenderer& operator=(const PingRenderer&) = delete;

  virtual RendererKind kind() const = 0;
  const SonarSetup& sonar() const { return sonar_; }
  const Fidelity& fidelity() const { return fidelity_; }

  // Renders the ping emitted from `pose` over `scene`. Randomness (speckle, noise) comes from
  // (seed, ping_index) only. scratch.traces holds the targets seen when options.truth is set.
  virtual void render(const scene::Scene& scene, const Pose& pose, std::uint64_t seed,
                      std::uint64_t ping_index, const RenderOptions& options, PingScratch& scratch,
                      PingLines& out) const = 0;

  // Makes, on the calling thread, what a ping from `pose` will read (profile: the heightmap tiles
  // along its ground lines, except those another thread is making, and the target BVH;
  // raytrace: its Embree view), so that rendering it later does not wait. Optional: render()
  // makes whatever is missing itself.
  virtual void prepare(const scene::Scene& scene, const Pose& pose, const RenderOptions& options,
                       PingScratch& scratch) const = 0;

  // The rectangle (north/east) a ping from `pose` can reach: max range around the sonar.
  scene::Box2 swath_region(const Pose& pose) const;

 protected:
  PingRenderer(const SonarSetup& sonar, const Fidelity& fidelity);
  const EchoModel& echo() const { return *echo_; }

  SonarSetup sonar_;
  Fidelity fidelity_;
  std::unique_ptr<EchoModel> echo_;
};

// A renderer of `kind` for `sonar`, with the default fidelity rule unless `fidelity` is given.
std::unique_ptr<PingRenderer> make_ping_renderer(RendererKind kind, const SonarSetup& sonar,
                                                 std::optional<Fidelity> fidelity = std::nullopt);

}  // namespace sonarloop::render
