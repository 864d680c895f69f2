#pragma once
// Labelled target chips for automatic target recognition (ATR), rendered as in Pailhas, Petillot
// & Capus (2010), Section 4: one target on a random seabed (flat, ripples, clutter), seen from a
// random altitude (2-10 m) and range (5-50 m) at a random orientation, by the strip sonar with
// isotropic pixels of size R (range bin = along-track resolution = ping spacing = R). Highlight
// chips are centred on the target; shadow chips (Section 4.2) put the target at a fixed 25 m
// ground range and extend far enough behind it to hold its whole shadow.
//
// Chip i is a pure function of (spec, i): its parameters come from Rng(seed, kDataset, i), its
// speckle and noise from a seed hashed from (seed, i, R). The same spec and index give the same
// bytes on any thread, in any order, with any number of threads.
//
// Chip geometry (fixed physical size per kind, so that round(size / R) pixels a side):
//   highlight   3 m along track x 3 m slant range, centred on the slant range of the target's
//               centre (the middle of its bounding box) at closest approach;
//   shadow      3 m along track x 10 m slant range, from 1 m before the target's centre:
//               a 0.5 m tall target 25 m away from a sonar 2 m up (the lowest altitude) casts
//               0.5·25/1.5 = 8.3 m of shadow, which ends 8.8 m beyond its centre.
// Rows are pings along track, columns range bins from near to far: column c is the slant-range
// bin [k0 + c, k0 + c + 1)·R, and the pings lie at along-track offsets (k - (rows-1)/2 + u)·R
// from the target's closest approach, k = 0, 1, ... in the order they were taken (u a random
// sub-pixel offset in [-0.5, 0.5)). Starboard chips put the last ping in row 0 (the direction of
// travel points up, as on a waterfall display), port chips the first: either way a chip is the
// seabed seen from above (not mirrored), turned so that the sonar looks to the right. A target
// at a given aspect therefore looks the same on either side.
//
// Aspect: aspect_deg = target heading - look direction (mod 360), where the look direction is
// the track heading + 90° (starboard) or - 90° (port): 0° = the target's long axis points
// away from the sonar (to the right in the chip), 90° = down the chip (clockwise, as headings).
//
// Pixel values: the level L = 20·log10(A) in dB re full scale, with A the relative amplitude of
// quantise.h (TVG applied; 0 dB = the echo of a -5 dB seabed at normal incidence); pixels are
// round(255·(L - min_db) / (max_db - min_db)) clipped to 0..255, over a FIXED span
// (ChipLevels, default -60..0 dB), never per-chip auto levels, so chips compare across the
// dataset. Speckle and noise are on, as on a real sonar.
//
// Efficiency ("only what the chip needs"): one large lazily tiled seabed per seabed kind is
// built once and shared by all chips (Scene's shared-seabed constructor), and one ping renderer
// per resolution; a chip renders only its own rows' pings, only its range window (plus
// kChipRangeMarginBins either side) and only the side it looks to. The profile renderer marches
// each row's ground line from kViewNearMargin_m before the window and traces the chip's one
// target; the ray tracer builds an Embree view of just the ground the window's rays reach.
// Chips are placed in blocks of kChipsPerBlock consecutive indices within a kBlockSize_m square
// (a random square of the seabed per block), so that neighbouring chips, rendered at the same
// time, reuse the seabed's heightmap tiles instead of synthesising new ones far apart.
//
// Limits: obstacles more than kViewNearMargin_m (ground) nearer to the sonar than the chip's
// range window are not considered, so the shadows they would cast into the chip are missing
// (targets and rocks inside and just before the window cast theirs).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/chip_convention.h"
#include "sim/frames.h"
#include "sim/render/ping_renderer.h"
#include "sim/render/sonar.h"
#include "sim/scene/scene.h"
#include "sim/scene/scene_desc.h"
#include "sim/targets/target_type.h"

namespace sonarloop::render {

// The chip convention (kinds, sizes, pixel levels) is common/chip_convention.h, shared with the
// onboard side (atr/), which cuts the same chips out of a live stream.
using chips::chip_kind_name;
using chips::chip_pixel;
using chips::ChipKind;
using chips::ChipLevels;
using chips::kHighlightChipAlong_m;
using chips::kHighlightChipRange_m;
using chips::kShadowChipAlong_m;
using chips::kShadowChipNear_m;
using chips::kShadowChipRange_m;
using chips::kShadowGroundRange_m;
// Range bins rendered beyond each end of the window and cropped, so that echoes spread across
// the window's edges (ray tubes, PingRenderer) reach its first and last columns as inside it.
inline constexpr int kChipRangeMarginBins = 2;
// Ground the chip's view extends towards the sonar before its range window (shadow casters) and
// beyond it (rising terrain), and along track beyond its pings.
inline constexpr double kViewNearMargin_m = 1.5;
inline constexpr double kViewFarMargin_m = 0.5;
inline constexpr double kViewAlongMargin_m = 0.25;
// Placement: kChipsPerBlock consecutive chips lie in one kBlockSize_m square of the seabed.
inline constexpr std::uint64_t kChipsPerBlock = 256;
inline constexpr double kBlockSize_m = 64.0;
// The shared seabed: a kDatasetSeabedSize_m square centred on the world origin (tiles are made
// only where chips land), with chips kept kDatasetSeabedMargin_m inside its edges so that a
// sonar 50 m away still sees seabed.
inline constexpr double kDatasetSeabedSize_m = 2000.0;
inline constexpr double kDatasetSeabedMargin_m = 80.0;

// One seabed kind: its name (CSV label) and a scene whose seed, water and seabed sections
// describe it (targets are ignored; the extent is replaced by the dataset's shared square).
struct DatasetSeabed {
  std::string name;
  scene::SceneDesc desc;
};

// How the looks k >= 1 at a dataset's objects (ChipDatasetSpec::look) are flown.
enum class LookGeometry {
  // each look a pass of its own: the sonar's altitude, ground range (highlight chips), track
  // heading and side drawn afresh
  kIndependent,
  // a lawnmower survey's neighbouring lines at one altitude: odd looks run the reciprocal track
  // past the object's other side (track heading + 180 deg, the object on the same side of the
  // vehicle, so seen from the opposite direction: aspect + 180 deg), even looks repeat look 0's
  // line; altitude and ground range stay look 0's
  kReciprocal,
};
const char* look_geometry_name(LookGeometry g);  // "independent", "reciprocal"
// Parses "independent" or "reciprocal"; nullopt otherwise.
std::optional<LookGeometry> parse_look_geometry(const std::string& name);

// The built-in kinds, mirroring config/seabed_<name>.yaml (Pailhas et al. 2010, Sec. 2.1):
// "flat" (very fine sand, no texture), "ripples" (very coarse sand, 0.8 m ripples), "clutter"
// (sandy gravel with about one rock per 10 m²), "rocky" (rough rock, eroded). All at 25 m depth
// on a 2.5 cm heightmap with gentle large-scale relief (0.15 m rms; rocky 0.3 m).
std::vector<std::string> builtin_dataset_seabed_names();
// Throws std::invalid_argument naming the available kinds for an unknown name.
DatasetSeabed builtin_dataset_seabed(const std::string& name);

struct ChipDatasetSpec {
  std::uint64_t seed = 0;
  ChipKind kind = ChipKind::kHighlight;
  // Chip i has class classes[i mod classes.size()] (balanced) and seabed
  // seabeds[(i / classes.size()) mod seabeds.size()] (every class on every seabed equally).
  std::vector<targets::TargetType> classes;
  std::vector<DatasetSeabed> seabeds;
  std::vector<double> resolutions_m;  // pixel sizes R; a chip is rendered at any of them
  double altitude_min_m = 2.0;        // sonar height above the target's base plane
  double altitude_max_m = 10.0;
  double range_min_m = 5.0;  // ground range from the track to the target's centre (highlight)
  double range_max_m = 50.0;
  // Target burial: the base sunk below the local seabed by this fraction of the target's height
  // (scene::TargetDesc::burial_m), 0 .. 0.9; the altitude stays measured from the seabed.
  double burial_fraction = 0.0;
  // The sonar (e.g. the pailhas_strip preset). Per resolution R the renderer sets: along_track
  // kStrip, bin_size_m = along_track_resolution_m = R, the pulse whose resolution is one bin
  // (pulse_length_s = chirp_bandwidth_hz = 0), and max_range_m large enough for every chip.
  SonarDesc sonar;
  ChipLevels levels;
  // The ping renderer (ping_renderer.h): the heightfield profile renderer by default, the
  // ray-traced reference on request.
  RendererKind renderer = RendererKind::kProfile;
  // Which look at the objects: 0, the dataset's own; k >= 1, the same objects (type, seabed,
  // position, heading) seen again from another pass, flown as look_geometry says; the
  // along-track offset and the speckle are drawn afresh for each k (multi-look fusion, `sweep
  // --looks`). Look 0 is the dataset as without these fields.
  int look = 0;
  LookGeometry look_geometry = LookGeometry::kIndependent;
};

// What chip `index` shows: a pure function of (spec, index), whatever the resolution.
struct ChipParams {
  std::uint64_t index = 0;
  targets::TargetType type = targets::TargetType::kManta;
  int seabed = 0;                   // into ChipDatasetSpec::seabeds
  double altitude_m = 0.0;          // sonar above the target's base plane
  double ground_range_m = 0.0;      // track to target centre, horizontal
  double target_heading_deg = 0.0;  // long axis, clockwise from north, [0, 360)
  double track_heading_deg = 0.0;   // direction of travel, clockwise from north, [0, 360)
  double aspect_deg = 0.0;          // target heading - look direction, [0, 360)
  int side = 1;                     // 0 port, 1 starboard
  Vec2 target_ne_m = Vec2::Zero();  // target centre, north/east on the shared seabed
  double along_offset = 0.0;        // u: sub-pixel along-track offset, in pixels, [-0.5, 0.5)
};

ChipParams chip_params(const ChipDatasetSpec& spec, std::uint64_t index);

struct ChipRowTruth {
  int highlight_first = -1;  // -1: the target is not seen in this row
  int highlight_last = -1;
  int shadow_first = -1;  // -1: no hidden seabed in this row
  int shadow_last = -1;
  double energy = 0.0;
};

// A rendered chip. Pixels are row-major, row 0 first (see the header comment for the axes).
struct ChipImage {
  ChipParams params;
  int resolution = 0;  // into ChipDatasetSpec::resolutions_m
  double resolution_m = 0.0;
  int rows = 0;                // pings
  int cols = 0;                // range bins
  double slant_range_m = 0.0;  // sonar to target centre at closest approach
  double range_start_m = 0.0;  // slant range of column 0's near edge
  // Chip coordinates (fractional pixel indices, pixel centres at integers) of the target's
  // centre.
  double target_row = 0.0;
  double target_col = 0.0;
  std::vector<float> level_db;       // (rows x cols) dB re full scale (-300 where no echo)
  std::vector<std::uint8_t> pixels;  // (rows x cols) the 8-bit chip
  // (rows x cols) per pixel kLabelSeabed, kLabelHighlight or kLabelShadow (values 0/1/2: the
  // ping renderer's per-bin labels, bin_labels.h), aligned with pixels
  std::vector<std::uint8_t> labels;
  // From the renderer's truth rays, per row: the columns where the target echoes and where
  // the seabed it hides lies (chip coordinates; they may reach beyond [0, cols)), and the
  // target's echo energy in that ping (linear, before speckle).
  std::vector<ChipRowTruth> truth;  // (rows)
};

// Renders chips of a dataset. Building it makes one shared seabed per seabed kind and one ping
// renderer per resolution: about 0.1-0.5 s. const methods are thread-safe.
class ChipRenderer {
 public:
  // Throws std::invalid_argument for an empty class, seabed or resolution list, a resolution
  // outside 5 mm..1 m, or bad altitude/range bounds.
  explicit ChipRenderer(ChipDatasetSpec spec);
  ~ChipRenderer();
  ChipRenderer(const ChipRenderer&) = delete;
  ChipRenderer& operator=(const ChipRenderer&) = delete;

  const ChipDatasetSpec& spec() const { return spec_; }
  // The sonar actually used at resolution slot r (after the per-resolution overrides).
  const SonarSetup& sonar(int resolution) const;
  // Chip size in pixels at a resolution: round(size / R), at least 1.
  int rows(int resolution) const;
  int cols(int resolution) const;

  // Renders chip `index` at resolutions_m[resolution], single-threaded.
  ChipImage render(std::uint64_t index, int resolution) const;

 private:
  struct Kind;
  ChipDatasetSpec spec_;
  std::vector<SonarSetup> sonars_;                        // per resolution
  std::vector<std::unique_ptr<PingRenderer>> renderers_;  // per resolution
  std::vector<std::unique_ptr<Kind>> kinds_;              // per seabed kind
};

// One chip to render: an index at a resolution slot.
struct ChipJob {
  std::uint64_t index = 0;
  int resolution = 0;
};

// Renders `jobs` with `threads` worker threads, each chip on one thread, and hands every chip
// to `sink` on the calling thread IN JOB ORDER (at most a few chips per thread are held while
// waiting for an earlier one). `stop` (optional, polled between chips) ends the run early: the
// chips already handed over are then exactly jobs[0, n) for the returned n. Returns the number
// of chips handed to the sink. An exception in a worker or in the sink stops the run and is
// rethrown here.
std::size_t render_chips(const ChipRenderer& renderer, std::span<const ChipJob> jobs, int threads,
                         const std::function<void(const ChipImage&)>& sink,
                         const std::function<bool()>& stop = {});

}  // namespace sonarloop::render
