#include "sim/render/chip_renderer.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <thread>

#include "common/rng.h"
#include "sim/render/quantise.h"
#include "sim/seabed/seabed_model.h"
#include "units/angles.h"

namespace sonarloop::render {
namespace {

// Sub-keys of RngStream::kDataset (the third hash key), one per use, never reused.
constexpr std::uint64_t kKeyChip = 0;    // (index): the chip's parameters
constexpr std::uint64_t kKeyBlock = 1;   // (block): where a block of chips lies
constexpr std::uint64_t kKeyRender = 2;  // (index, R): speckle and noise of a chip
constexpr std::uint64_t kKeySeabed = 3;  // (kind seed): the seed of a shared seabed
constexpr std::uint64_t kKeyLook = 4;    // (index, look >= 1): another pass over the object

// Resolutions accepted: 5 mm (a wavelength at 300 kHz) to 1 m.
constexpr double kMinResolution_m = 0.005;
constexpr double kMaxResolution_m = 1.0;

// Heightmap tiles of the shared seabeds: 64 points (1.6 m at 2.5 cm) instead of the scene
// default 256, because a chip's view covers a few metres: a small tile wastes less terrain
// synthesis at the view's edges. A tile is a pure function of its lattice points, so the tile
// size changes no height. The caches of each seabed hold up to 128 MB: its noise layers 8 MB
// each, the heightmap tiles (20 kB each) the rest (seabed_model.h). With 64 MB a noise layer
// held 4 pairs of its 6.4 m tiles and remade them across a block's 64 m square: a fig11 sweep
// at 5 cm (100 training and 300 test chips per target, one thread) took 12-15 % longer, for
// 116 MB less peak memory. The tiles, and so the chips, are the same whatever the cache.
constexpr int kSeabedTileSize = 64;
constexpr std::size_t kSeabedCacheBytes = 128u << 20;

// Level of a bin with no echo at all (no noise, no seabed): below any span.
constexpr double kNoEchoDb = -300.0;

// Heights around a chip's target, relative to its base plane. For the extent of a chip's view:
// the seabed lies within kSeabedNearBase_m of it (relief over a few metres, textures). For the
// sonar's maximum range (which must hold every chip's widened ray fan, see render()): nothing
// stands higher than the target or a clutter rock (kMaxRockHeight_m: 1 m maximum diameter x
// 0.5 height ratio, config/seabed_cluttered.yaml) plus kReliefAcrossWindow_m, and the nadir
// seabed lies at most kNadirBelowBase_m below the base (large-scale relief between points up
// to ~60 m apart). kMinClearanceFraction bounds the fan when something reaches nearly to the
// sonar's height.
constexpr double kSeabedNearBase_m = 0.5;
constexpr double kMaxRockHeight_m = 0.5;
constexpr double kReliefAcrossWindow_m = 0.1;
constexpr double kMinClearanceFraction = 0.25;
constexpr double kNadirBelowBase_m = 1.0;

int pixels_for(double size_m, double resolution_m) {
  return std::max(1, static_cast<int>(std::lround(size_m / resolution_m)));
}

double chip_along_m(ChipKind k) {
  return k == ChipKind::kShadow ? kShadowChipAlong_m : kHighlightChipAlong_m;
}
double chip_range_m(ChipKind k) {
  return k == ChipKind::kShadow ? kShadowChipRange_m : kHighlightChipRange_m;
}

scene::SceneDesc base_seabed_desc(std::uint64_t seed, const char* sediment) {
  scene::SceneDesc d;
  d.seed = seed;
  d.name = "dataset";
  d.water.depth_m = 25.0;
  d.seabed.grid_spacing_m = 0.025;
  d.seabed.elevation.rms_m = 0.15;
  d.seabed.elevation.beta = 1.8;
  d.seabed.elevation.outer_scale_m = 40.0;
  scene::RegionDesc r;
  r.sediment = *seabed::find_sediment(sediment);
  r.centre_m = Vec2::Zero();
  d.seabed.regions = {r};
  return d;
}

// World z (down) of the highest and the deepest heightmap point in `region` (making its tiles).
std::pair<double, double> seabed_depth_range(const seabed::SeabedModel& seabed,
                                             const scene::Box2& region) {
  const double d = seabed.spacing_m();
  const auto ia = static_cast<std::int64_t>(std::floor(region.min.x() / d));
  const auto ib = static_cast<std::int64_t>(std::ceil(region.max.x() / d));
  const auto ja = static_cast<std::int64_t>(std::floor(region.min.y() / d));
  const auto jb = static_cast<std::int64_t>(std::ceil(region.max.y() / d));
  const int ni = static_cast<int>(ib - ia + 1);
  const int nj = static_cast<int>(jb - ja + 1);
  std::vector<float> h(static_cast<std::size_t>(ni) * static_cast<std::size_t>(nj));
  seabed.copy_region(ia, ja, ni, nj, h.data(), nullptr);
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  return {seabed.water_depth_m() - *hi, seabed.water_depth_m() - *lo};
}

}  // namespace

std::vector<std::string> builtin_dataset_seabed_names() {
  return {"flat", "ripples", "clutter", "rocky"};
}

DatasetSeabed builtin_dataset_seabed(const std::string& name) {
  // the values of config/seabed_<name>.yaml (chip_renderer_test checks they agree)
  DatasetSeabed s;
  s.name = name;
  if (name == "flat") {
    s.desc = base_seabed_desc(11, "very_fine_sand");
  } else if (name == "ripples") {
    s.desc = base_seabed_desc(12, "very_coarse_sand");
    s.desc.seabed.regions[0].texture.ripples = scene::RipplesDesc{0.8, 30.0, 2.0, 2.5, 0.05};
  } else if (name == "clutter") {
    s.desc = base_seabed_desc(14, "sandy_gravel");
    s.desc.seabed.regions[0].texture.clutter = scene::ClutterDesc{0.1, 0.25, 0.5, 0.5, 1.0};
  } else if (name == "rocky") {
    s.desc = base_seabed_desc(13, "rough_rock");
    s.desc.seabed.elevation.rms_m = 0.3;
    s.desc.seabed.regions[0].texture.rocky = scene::RockyDesc{0.08, 3.2, 3.0, 20.0, 2.0};
  } else {
    std::string list;
    for (const auto& n : builtin_dataset_seabed_names())
      list += (list.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown seabed kind '" + name + "' (built-in kinds: " + list +
                                ")");
  }
  return s;
}

const char* look_geometry_name(LookGeometry g) {
  return g == LookGeometry::kReciprocal ? "reciprocal" : "independent";
}

std::optional<LookGeometry> parse_look_geometry(const std::string& name) {
  if (name == "independent") return LookGeometry::kIndependent;
  if (name == "reciprocal") return LookGeometry::kReciprocal;
  return std::nullopt;
}

ChipParams chip_params(const ChipDatasetSpec& spec, std::uint64_t index) {
  if (spec.classes.empty() || spec.seabeds.empty()) {
    throw std::invalid_argument("chip_params: the dataset has no classes or no seabeds");
  }
  ChipParams p;
  p.index = index;
  const std::uint64_t n_classes = spec.classes.size();
  p.type = spec.classes[index % n_classes];
  p.seabed = static_cast<int>((index / n_classes) % spec.seabeds.size());
  // draws in a fixed order, all of them for every kind, so that a highlight and a shadow
  // dataset of the same seed show the same scenes apart from the shadow chips' fixed range
  Rng rng(spec.seed, RngStream::kDataset, index, kKeyChip);
  p.altitude_m = rng.uniform(spec.altitude_min_m, spec.altitude_max_m);
  const double ground = rng.uniform(spec.range_min_m, spec.range_max_m);
  p.ground_range_m = spec.kind == ChipKind::kShadow ? kShadowGroundRange_m : ground;
  p.target_heading_deg = wrap_to_360_deg(rng.uniform(0.0, 360.0));
  p.track_heading_deg = wrap_to_360_deg(rng.uniform(0.0, 360.0));
  p.side = static_cast<int>(rng.below(2));
  const double block_x = rng.uniform(0.0, kBlockSize_m);
  const double block_y = rng.uniform(0.0, kBlockSize_m);
  p.along_offset = rng.uniform(-0.5, 0.5);
  // the block's south-west corner, anywhere on the shared seabed inside its margins
  Rng block(spec.seed, RngStream::kDataset, index / kChipsPerBlock, kKeyBlock);
  const double lo = -0.5 * kDatasetSeabedSize_m + kDatasetSeabedMargin_m;
  const double span = kDatasetSeabedSize_m - 2.0 * kDatasetSeabedMargin_m - kBlockSize_m;
  const double corner_x = lo + block.uniform(0.0, span);
  const double corner_y = lo + block.uniform(0.0, span);
  p.target_ne_m = Vec2(corner_x + block_x, corner_y + block_y);
  if (spec.look > 0) {  // the same object from another pass (every draw made in either mode)
    Rng pass(spec.seed, RngStream::kDataset, index, kKeyLook,
             static_cast<std::uint64_t>(spec.look));
    const double altitude = pass.uniform(spec.altitude_min_m, spec.altitude_max_m);
    const double pass_ground = pass.uniform(spec.range_min_m, spec.range_max_m);
    const double track = wrap_to_360_deg(pass.uniform(0.0, 360.0));
    const int side = static_cast<int>(pass.below(2));
    p.along_offset = pass.uniform(-0.5, 0.5);
    if (spec.look_geometry == LookGeometry::kIndependent) {
      p.altitude_m = altitude;
      if (spec.kind != ChipKind::kShadow) p.ground_range_m = pass_ground;
      p.track_heading_deg = track;
      p.side = side;
    } else if (spec.look % 2 == 1) {  // the reciprocal line, past the object's other side
      p.track_heading_deg = wrap_to_360_deg(p.track_heading_deg + 180.0);
    }
  }
  const double look_deg = p.track_heading_deg + (p.side == 1 ? 90.0 : -90.0);
  p.aspect_deg = wrap_to_360_deg(p.target_heading_deg - look_deg);
  return p;
}

// One seabed kind: the shared seabed all its chips' scenes are placed on.
struct ChipRenderer::Kind {
  scene::SceneDesc desc;  // the shared seabed's scene, no targets
  std::shared_ptr<const seabed::SeabedModel> seabed;
};

ChipRenderer::ChipRenderer(ChipDatasetSpec spec) : spec_(std::move(spec)) {
  if (spec_.classes.empty()) throw std::invalid_argument("dataset: no target classes");
  if (spec_.seabeds.empty()) throw std::invalid_argument("dataset: no seabed kinds");
  if (spec_.resolutions_m.empty()) throw std::invalid_argument("dataset: no resolutions");
  for (double r : spec_.resolutions_m) {
    if (!(r >= kMinResolution_m && r <= kMaxResolution_m)) {
      throw std::invalid_argument("dataset: resolution " + std::to_string(r) +
                                  " m is outside 0.005..1 m");
    }
  }
  if (!(spec_.altitude_min_m > 0.0 && spec_.altitude_min_m <= spec_.altitude_max_m)) {
    throw std::invalid_argument("dataset: need 0 < altitude_min_m <= altitude_max_m");
  }
  if (!(spec_.burial_fraction >= 0.0 && spec_.burial_fraction <= 0.9)) {
    throw std::invalid_argument("dataset: burial fraction must be within 0 .. 0.9");
  }
  if (!(spec_.range_min_m > 0.0 && spec_.range_min_m <= spec_.range_max_m)) {
    throw std::invalid_argument("dataset: need 0 < range_min_m <= range_max_m");
  }
  if (spec_.look < 0) throw std::invalid_argument("dataset: the look must be 0 or more");
  // the sonar per resolution: isotropic pixels of R, one-bin pulse, and a maximum range that
  // holds every chip's widened ray fan (see render())
  const double ground_max =
      spec_.kind == ChipKind::kShadow ? kShadowGroundRange_m : spec_.range_max_m;
  const double beyond = spec_.kind == ChipKind::kShadow ? kShadowChipRange_m - kShadowChipNear_m
                                                        : 0.5 * kHighlightChipRange_m;
  const double r_res_max =
      *std::max_element(spec_.resolutions_m.begin(), spec_.resolutions_m.end());
  double height_max = kMaxRockHeight_m;
  for (targets::TargetType t : spec_.classes)
    height_max = std::max(height_max, targets::target_type_info(t).size_m.z());
  const double r_hi_max = std::hypot(ground_max + 1.0, spec_.altitude_max_m) + beyond +
                          (kChipRangeMarginBins + 2) * r_res_max;
  double fan_ratio = 1.0;  // largest a_n / (a - above) over the altitudes
  for (double a : {spec_.altitude_min_m, spec_.altitude_max_m}) {
    const double clearance =
        std::max(a - height_max - kReliefAcrossWindow_m, kMinClearanceFraction * a);
    fan_ratio = std::max(fan_ratio, (a + kNadirBelowBase_m) / clearance);
  }
  const double max_range = std::ceil(r_hi_max * fan_ratio) + 1.0;
  for (double r : spec_.resolutions_m) {
    SonarDesc sd = spec_.sonar;
    sd.along_track = AlongTrackModel::kStrip;
    sd.bin_size_m = r;
    sd.along_track_resolution_m = r;
    sd.pulse_length_s = 0.0;
    sd.chirp_bandwidth_hz = 0.0;
    sd.max_range_m = max_range;
    sonars_.push_back(make_sonar_setup(sd, spec_.seabeds[0].desc.water));
    renderers_.push_back(make_ping_renderer(spec_.renderer, sonars_.back()));
  }
  seabed::SeabedOptions options;
  options.tile_size = kSeabedTileSize;
  options.cache_bytes = kSeabedCacheBytes;
  for (const DatasetSeabed& s : spec_.seabeds) {
    auto k = std::make_unique<Kind>();
    k->desc = s.desc;
    k->desc.targets.clear();
    k->desc.seed = hash_keys(spec_.seed, RngStream::kDataset, s.desc.seed, kKeySeabed);
    k->desc.seabed.origin_m = Vec2::Constant(-0.5 * kDatasetSeabedSize_m);
    k->desc.seabed.extent_m = Vec2::Constant(kDatasetSeabedSize_m);
    if (s.desc.water.depth_m != spec_.seabeds[0].desc.water.depth_m ||
        s.desc.water.temperature_c != spec_.seabeds[0].desc.water.temperature_c ||
        s.desc.water.salinity_ppt != spec_.seabeds[0].desc.water.salinity_ppt) {
      // the sonar setups (absorption, sound speed) are made once for the first kind's water
      throw std::invalid_argument("dataset: seabed kind '" + s.name + "' has other water than '" +
                                  spec_.seabeds[0].name +
                                  "'; all kinds must share one water column");
    }
    k->seabed = std::make_shared<const seabed::SeabedModel>(k->desc, options);
    kinds_.push_back(std::move(k));
  }
}

ChipRenderer::~ChipRenderer() = default;

const SonarSetup& ChipRenderer::sonar(int resolution) const {
  return sonars_.at(static_cast<std::size_t>(resolution));
}

int ChipRenderer::rows(int resolution) const {
  return pixels_for(chip_along_m(spec_.kind),
                    spec_.resolutions_m.at(static_cast<std::size_t>(resolution)));
}

int ChipRenderer::cols(int resolution) const {
  return pixels_for(chip_range_m(spec_.kind),
                    spec_.resolutions_m.at(static_cast<std::size_t>(resolution)));
}

ChipImage ChipRenderer::render(std::uint64_t index, int resolution) const {
  const SonarSetup& setup = sonar(resolution);
  const double res = setup.desc.bin_size_m;
  ChipImage chip;
  chip.params = chip_params(spec_, index);
  const ChipParams& p = chip.params;
  chip.resolution = resolution;
  chip.resolution_m = spec_.resolutions_m[static_cast<std::size_t>(resolution)];
  chip.rows = rows(resolution);
  chip.cols = cols(resolution);
  const Kind& kind = *kinds_[static_cast<std::size_t>(p.seabed)];

  // the chip's scene: its target on the shared seabed
  scene::SceneDesc desc = kind.desc;
  scene::TargetDesc target;
  target.name = "target";
  target.type = p.type;
  target.position_m = p.target_ne_m;
  target.heading_deg = p.target_heading_deg;
  target.burial_m = spec_.burial_fraction * targets::target_type_info(p.type).size_m.z();
  desc.targets = {target};
  const scene::Scene sc(desc, kind.seabed);
  const scene::PlacedTarget& placed = sc.targets()[0];
  const Vec3 centre = placed.bounds_W.center();
  // the base plane lies burial_m below the seabed (z down): the altitude is above the seabed
  const double sonar_z = placed.X_WT.translation().z() - target.burial_m - p.altitude_m;

  // the track: closest approach to the target's centre at along-track offset 0
  const Vec2 along = heading_vector(p.track_heading_deg * kRadPerDeg);
  const Vec2 look = p.side == 1 ? Vec2(-along.y(), along.x()) : Vec2(along.y(), -along.x());
  const Vec2 closest = p.target_ne_m - p.ground_range_m * look;
  chip.slant_range_m = (centre - Vec3(closest.x(), closest.y(), sonar_z)).norm();

  // range window: bins [k0, k0 + cols)
  const double near_m = spec_.kind == ChipKind::kShadow
                            ? chip.slant_range_m - kShadowChipNear_m
                            : chip.slant_range_m - 0.5 * kHighlightChipRange_m;
  const int k0 = std::max(kChipRangeMarginBins, static_cast<int>(std::lround(near_m / res)));
  chip.range_start_m = k0 * res;
  chip.target_col = chip.slant_range_m / res - k0 - 0.5;
  const double centre_row = 0.5 * (chip.rows - 1);
  // starboard: the last ping in row 0; port: the first (see the header)
  chip.target_row = p.side == 1 ? centre_row + p.along_offset : centre_row - p.along_offset;

  // the chip's window [r_lo, r_hi) in slant range, with margin bins either side
  const double r_lo = (k0 - kChipRangeMarginBins) * res;
  const double r_hi = (k0 + chip.cols + kChipRangeMarginBins) * res;

  // the view: the ground the window's rays can reach, over all the chip's pings, taking the
  // seabed to lie within kSeabedNearBase_m of the target's base plane
  const double a = p.altitude_m;
  const double a_deep = a + kSeabedNearBase_m;
  const double a_high = std::max(0.0, a - kSeabedNearBase_m);
  const double g_near =
      std::max(0.0, std::sqrt(std::max(0.0, r_lo * r_lo - a_deep * a_deep)) - kViewNearMargin_m);
  const double g_far = std::sqrt(std::max(0.0, r_hi * r_hi - a_high * a_high)) + kViewFarMargin_m;
  const double s_first = (-centre_row + p.along_offset) * res;
  const double s_last = (centre_row + p.along_offset) * res;
  scene::Box2 region{Vec2::Constant(1e300), Vec2::Constant(-1e300)};
  for (double s : {s_first - res - kViewAlongMargin_m, s_last + res + kViewAlongMargin_m}) {
    for (double g : {g_near, g_far}) {
      const Vec2 q = closest + s * along + g * look;
      region.min = region.min.cwiseMin(q);
      region.max = region.max.cwiseMax(q);
    }
  }
  const PingRenderer& renderer = *renderers_[static_cast<std::size_t>(resolution)];
  const bool raytrace = renderer.kind() == RendererKind::kRaytrace;

  // The ray tracer fans its rays where a flat seabed at the nadir altitude a_n would put the
  // window's ranges: a ray of depression δ is meant for slant range a_n / sin δ. The view's
  // seabed lies at other depths (relief, textures) and holds taller things (the target,
  // rocks), so its fan is widened to every depression that can land in the window: from its
  // near edge on the deepest seabed of the view, to its far edge on the highest point. (The
  // profile renderer marches the ground itself and lays its target rays out over the target.)
  double d_deep = 0.0, d_high = 0.0;
  if (raytrace) {
    const scene::Box2 clipped{region.min.cwiseMax(kind.seabed->extent_min()),
                              region.max.cwiseMin(kind.seabed->extent_max())};
    const auto [seabed_high, seabed_deep] = seabed_depth_range(*kind.seabed, clipped);
    const double depth_high = std::min(seabed_high, placed.bounds_W.min().z());
    d_deep = std::max(seabed_deep - sonar_z, 1e-3);
    d_high = std::max(depth_high - sonar_z, kMinClearanceFraction * a);
  }

  // the pings, one per row
  std::uint64_t seed = hash_keys(spec_.seed, RngStream::kDataset, index, kKeyRender,
                                 std::bit_cast<std::uint64_t>(chip.resolution_m));
  if (spec_.look > 0) seed = hash_keys(seed, kKeyLook, static_cast<std::uint64_t>(spec_.look));
  const auto n = static_cast<std::size_t>(chip.rows) * static_cast<std::size_t>(chip.cols);
  chip.level_db.assign(n, 0.0f);
  chip.pixels.assign(n, 0);
  chip.labels.assign(n, kLabelSeabed);
  chip.truth.assign(static_cast<std::size_t>(chip.rows), ChipRowTruth{});
  PingScratch scratch;
  PingLines lines;
  for (int k = 0; k < chip.rows; ++k) {
    Pose pose;
    const Vec2 xy = closest + (k - centre_row + p.along_offset) * res * along;
    pose.position_W = Vec3(xy.x(), xy.y(), sonar_z);
    pose.yaw = p.track_heading_deg * kRadPerDeg;
    RenderOptions options;
    options.truth = true;
    options.labels = true;
    options.side_mask = 1 << p.side;
    options.shadow_margin_m = kViewNearMargin_m;
    if (raytrace) {
      // a_n: the seabed depth below the sonar, as the ray tracer finds it (its nadir ray misses
      // the chip's view and falls back to the heightmap)
      const double a_n = sc.seabed_z(xy.x(), xy.y()) - sonar_z;
      options.view_region = region;
      // a hair inside the window, so that floor() in the renderer cannot step back a bin
      options.range_min_m = std::min(r_lo + 1e-6 * res, a_n * r_lo / d_deep);
      // the renderer fans 5 % beyond range_max_m
      options.range_max_m = std::max(r_hi, a_n * r_hi / d_high / 1.05);
    } else {
      // the sonar's height above the large-scale seabed below it: the profile renderer needs it
      // only to lay out target rays, and this needs no heightmap tile at nadir
      options.nadir_altitude_m =
          sc.seabed().water_depth_m() - sc.seabed().base_elevation(xy.x(), xy.y()) - sonar_z;
      options.range_min_m = r_lo + 1e-6 * res;
      options.range_max_m = r_hi;
    }
    renderer.render(sc, pose, seed, static_cast<std::uint64_t>(k), options, scratch, lines);
    const std::vector<float>& line = p.side == 1 ? lines.stbd : lines.port;
    const std::vector<std::uint8_t>& label = p.side == 1 ? lines.stbd_label : lines.port_label;
    const int row = p.side == 1 ? chip.rows - 1 - k : k;
    for (int c = 0; c < chip.cols; ++c) {
      const int bin = k0 + c;
      const double amp =
          relative_amplitude(setup, line[static_cast<std::size_t>(bin)], (bin + 0.5) * res);
      const double level = amp > 0.0 ? 20.0 * std::log10(amp) : kNoEchoDb;
      const std::size_t m = static_cast<std::size_t>(row) * static_cast<std::size_t>(chip.cols) +
                            static_cast<std::size_t>(c);
      chip.level_db[m] = static_cast<float>(level);
      chip.pixels[m] = chip_pixel(level, spec_.levels);
      chip.labels[m] = label[static_cast<std::size_t>(bin)];
    }
    ChipRowTruth& t = chip.truth[static_cast<std::size_t>(row)];
    for (const TargetTrace& tr : scratch.traces) {
      if (tr.side != p.side) continue;
      if (tr.highlight_first >= 0) {
        t.highlight_first = tr.highlight_first - k0;
        t.highlight_last = tr.highlight_last - k0;
        t.energy = tr.energy;
      }
      if (tr.shadow_first >= 0) {
        t.shadow_first = tr.shadow_first - k0;
        t.shadow_last = tr.shadow_last - k0;
      }
    }
  }
  return chip;
}

std::size_t render_chips(const ChipRenderer& renderer, std::span<const ChipJob> jobs, int threads,
                         const std::function<void(const ChipImage&)>& sink,
                         const std::function<bool()>& stop) {
  const std::size_t n = jobs.size();
  if (n == 0) return 0;
  const auto workers = static_cast<std::size_t>(
      std::clamp<std::size_t>(static_cast<std::size_t>(std::max(1, threads)), 1, n));
  // chips finished out of order wait in a ring of `window` slots for the earlier ones
  const std::size_t window = 4 * workers + 4;
  std::vector<std::optional<ChipImage>> slots(window);
  std::mutex mutex;
  std::condition_variable work_cv;  // a slot came free, or the run ends
  std::condition_variable done_cv;  // a chip is ready, or a worker left
  std::size_t next = 0;             // next job to take
  std::size_t emitted = 0;          // jobs handed to the sink
  std::size_t active = workers;
  bool halt = false;  // stop requested, or an exception
  std::exception_ptr error;

  auto work = [&] {
    for (;;) {
      std::size_t j = 0;
      {
        std::unique_lock lock(mutex);
        work_cv.wait(lock, [&] { return halt || next >= n || next < emitted + window; });
        if (halt || next >= n) break;
        j = next++;
      }
      try {
        if (stop && stop()) {
          const std::lock_guard lock(mutex);
          halt = true;
          break;
        }
        ChipImage chip = renderer.render(jobs[j].index, jobs[j].resolution);
        const std::lock_guard lock(mutex);
        slots[j % window] = std::move(chip);
      } catch (...) {
        const std::lock_guard lock(mutex);
        if (!error) error = std::current_exception();
        halt = true;
        break;
      }
      done_cv.notify_one();
    }
    {
      const std::lock_guard lock(mutex);
      --active;
    }
    work_cv.notify_all();
    done_cv.notify_one();
  };
  std::vector<std::thread> pool;
  pool.reserve(workers);
  for (std::size_t t = 0; t < workers; ++t)
    pool.emplace_back(work);

  // hand chips over in job order on this thread
  while (emitted < n) {
    std::optional<ChipImage> chip;
    {
      std::unique_lock lock(mutex);
      done_cv.wait(lock, [&] { return halt || active == 0 || slots[emitted % window]; });
      if (halt || !slots[emitted % window]) break;
      chip = std::move(slots[emitted % window]);
      slots[emitted % window].reset();
    }
    try {
      sink(*chip);
    } catch (...) {
      const std::lock_guard lock(mutex);
      if (!error) error = std::current_exception();
      halt = true;
    }
    {
      const std::lock_guard lock(mutex);
      if (halt) break;
      ++emitted;
    }
    work_cv.notify_all();
  }
  {
    const std::lock_guard lock(mutex);
    halt = true;
  }
  work_cv.notify_all();
  for (auto& t : pool)
    t.join();
  if (error) std::rethrow_exception(error);
  return emitted;
}

}  // namespace sonarloop::render
