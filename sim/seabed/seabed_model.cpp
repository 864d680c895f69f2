#include "sim/seabed/seabed_model.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "common/parallel_for.h"
#include "sim/core/integer_division.h"
#include "sim/seabed/layer_rules.h"
#include "sim/seabed/spectra.h"
#include "units/angles.h"

namespace sonarloop::seabed {
namespace {

// Model ids: a counter, not randomness (ids never reach an output).
std::atomic<std::uint64_t> g_next_model_uid{1};

std::unique_ptr<NoiseLayer> make_elevation(const scene::SceneDesc& desc, std::size_t cache_bytes) {
  const auto& e = desc.seabed.elevation;
  if (e.rms_m <= 0.0) return nullptr;
  NoiseLayerSpec s;
  s.seed = desc.seed;
  s.stream = RngStream::kElevation;
  s.spacing_m = e.spacing_m;
  s.kernel_size = kernel_size_for(pink_kernel_extent_m(e.outer_scale_m), e.spacing_m);
  s.rms = e.rms_m;
  // YAML beta is the 1-D profile exponent; the isotropic 2-D spectrum falls one power faster
  const double beta_2d = profile_to_surface_exponent(e.beta);
  const double outer = e.outer_scale_m;
  const double inner = e.inner_scale_m;
  s.spectrum = [=](double fx, double fy) { return pink_psd(fx, fy, beta_2d, outer, inner); };
  s.kernel_key = spectrum_key("pink", {beta_2d, outer, inner});
  return std::make_unique<NoiseLayer>(std::move(s), cache_bytes);
}

std::unique_ptr<NoiseLayer> make_ripples(const scene::SceneDesc& desc, std::size_t region,
                                         const scene::RipplesDesc& r, std::size_t cache_bytes) {
  if (r.height_m <= 0.0) return nullptr;
  NoiseLayerSpec s;
  s.seed = desc.seed;
  s.stream = RngStream::kRipples;
  s.sub_key = region;
  s.spacing_m = ripple_spacing_m(r.wavelength_m);
  s.kernel_size = kernel_size_for(ripple_kernel_extent_m(r.wavelength_m), s.spacing_m);
  s.rms = r.height_m;
  // one frequency bin of the kernel's synthesis grid regularises the spectrum's singular lines
  const double eps = 1.0 / (2.0 * s.kernel_size * s.spacing_m);
  const double wl = r.wavelength_m;
  const double dir = r.direction_deg * kRadPerDeg;
  const double b1 = r.beta1;
  const double b = r.beta;
  s.spectrum = [=](double fx, double fy) { return ripple_psd(fx, fy, wl, dir, b1, b, eps); };
  s.kernel_key = spectrum_key("ripple", {wl, dir, b1, b, eps});
  return std::make_unique<NoiseLayer>(std::move(s), cache_bytes);
}

std::unique_ptr<NoiseLayer> make_rocky(const scene::SceneDesc& desc, std::size_t region,
                                       const scene::RockyDesc& r, std::size_t cache_bytes) {
  if (r.rms_m <= 0.0) return nullptr;
  NoiseLayerSpec s;
  s.seed = desc.seed;
  s.stream = RngStream::kRocky;
  s.sub_key = region;
  s.spacing_m = rocky_spacing_m(r.outer_scale_m);
  s.kernel_size =
      kernel_size_for(rocky_kernel_extent_m(r.outer_scale_m, r.anisotropy), s.spacing_m);
  s.rms = r.rms_m;
  const double beta = r.beta;
  const double aniso = r.anisotropy;
  const double dir = r.direction_deg * kRadPerDeg;
  const double outer = r.outer_scale_m;
  s.spectrum = [=](double fx, double fy) { return rocky_psd(fx, fy, beta, aniso, dir, outer); };
  s.kernel_key = spectrum_key("rocky", {beta, aniso, dir, outer});
  return std::make_unique<NoiseLayer>(std::move(s), cache_bytes);
}

void check_level(int level) {
  if (level < 0 || level > kMaxSeabedLevel) {
    throw std::out_of_range("seabed detail level " + std::to_string(level) + " is outside 0.." +
                            std::to_string(kMaxSeabedLevel));
  }
}
// make_tile's per-point buffers (region, blend weights, texture), kept per thread (as
// NoiseLayer::sample_grid's buffers are).
struct TileScratch {
  std::vector<std::uint8_t> region;
  std::array<std::vector<float>, kMaxRegions> weight;
  std::vector<float> tex;
};
TileScratch& tile_scratch() {
  thread_local TileScratch t;
  return t;
}

}  // namespace

SeabedModel::SeabedModel(const scene::SceneDesc& desc, SeabedOptions options)
    : options_(options),
      uid_(g_next_model_uid++),
      spacing_m_(desc.seabed.grid_spacing_m),
      water_depth_m_(desc.water.depth_m),
      slope_(desc.seabed.elevation.slope),
      relief_(desc.seabed.bathymetry ? desc.seabed.bathymetry->grid : nullptr),
      extent_min_(desc.seabed.origin_m),
      extent_max_(desc.seabed.origin_m + desc.seabed.extent_m),
      elevation_(make_elevation(desc, options.cache_bytes / kNoiseLayerBudgetShare)),
      partition_(desc, options.cache_bytes / kNoiseLayerBudgetShare),
      clutter_(
          desc, [this](double x, double y) { return partition_.region_at(x, y); },
          [this](double x, double y) { return base_elevation(x, y); }),
      cache_(kMinHeightTiles) {
  const std::size_t layer_bytes = options.cache_bytes / kNoiseLayerBudgetShare;
  for (std::size_t k = 0; k < desc.seabed.regions.size(); ++k) {
    const auto& r = desc.seabed.regions[k];
    RegionLayers layers;
    layers.sediment = r.sediment;
    if (r.texture.ripples) layers.ripples = make_ripples(desc, k, *r.texture.ripples, layer_bytes);
    if (r.texture.rocky) layers.rocky = make_rocky(desc, k, *r.texture.rocky, layer_bytes);
    regions_.push_back(std::move(layers));
  }
  if (regions_.empty()) {
    regions_.push_back(RegionLayers{*find_sediment("medium_sand"), nullptr, nullptr});
  }
  // the heightmap tiles get what the noise layers leave of the budget
  std::size_t noise_bytes = 0;
  for (const NoiseLayer* l : noise_layers())
    noise_bytes += l->cache_counters().capacity * l->cache_entry_bytes();
  const std::size_t left =
      options.cache_bytes > noise_bytes ? options.cache_bytes - noise_bytes : 0;
  cache_.set_capacity(std::max(kMinHeightTiles, left / height_tile_bytes(options.tile_size)));
}

std::vector<const NoiseLayer*> SeabedModel::noise_layers() const {
  std::vector<const NoiseLayer*> out = partition_.noise_layers();
  if (elevation_) out.push_back(elevation_.get());
  for (const RegionLayers& r : regions_) {
    if (r.ripples) out.push_back(r.ripples.get());
    if (r.rocky) out.push_back(r.rocky.get());
  }
  return out;
}

SeabedCacheStats SeabedModel::cache_stats() const {
  SeabedCacheStats s;
  s.heightmap = cache_.counters();
  s.bytes = s.heightmap.tiles * height_tile_bytes(options_.tile_size);
  s.budget_bytes = s.heightmap.capacity * height_tile_bytes(options_.tile_size);
  for (const NoiseLayer* l : noise_layers()) {
    const TileCacheCounters c = l->cache_counters();
    s.noise += c;
    s.bytes += c.tiles * l->cache_entry_bytes();
    s.budget_bytes += c.capacity * l->cache_entry_bytes();
  }
  return s;
}

std::int64_t SeabedModel::tile_of(std::int64_t i) const {
  return floor_div(i, options_.tile_size);
}

double SeabedModel::base_elevation(double x, double y) const {
  double h = slope_.x() * x + slope_.y() * y;
  if (relief_) h += relief_at(*relief_, x, y);
  if (elevation_) h += elevation_->sample(x, y);
  return h;
}

std::shared_ptr<const HeightTile> SeabedModel::tile(std::int64_t ti, std::int64_t tj,
                                                    int level) const {
  check_level(level);
  return cache_.get({ti, tj, level}, [&] { return make_tile(ti, tj, level); });
}

void SeabedModel::prefetch_tile(std::int64_t ti, std::int64_t tj, int level) const {
  check_level(level);
  cache_.prefetch({ti, tj, level}, [&] { return make_tile(ti, tj, level); });
}

std::shared_ptr<const HeightTile> SeabedModel::make_tile(std::int64_t ti, std::int64_t tj,
                                                         int level) const {
  const int t = options_.tile_size;
  const auto tt = static_cast<std::size_t>(t);
  const double d = spacing_m(level);
  const double x0 = static_cast<double>(ti * t) * d;
  const double y0 = static_cast<double>(tj * t) * d;
  tiles_made_.fetch_add(1, std::memory_order_relaxed);
  auto tile = std::make_shared<HeightTile>();
  tile->ti = ti;
  tile->tj = tj;
  tile->level = level;
  tile->size = t;
  auto& h = tile->elevation_m;
  h.resize(tt * tt);
  // elevation layer: plane (+ a bathymetry grid's relief) + smoothed pink noise
  for (int r = 0; r < t; ++r) {
    for (int c = 0; c < t; ++c) {
      h[static_cast<std::size_t>(r) * tt + static_cast<std::size_t>(c)] =
          static_cast<float>(slope_.x() * (x0 + r * d) + slope_.y() * (y0 + c * d));
    }
  }
  if (relief_) add_relief(*relief_, x0, y0, d, t, t, h.data(), tt);
  if (elevation_) elevation_->sample_grid(x0, y0, d, t, t, h.data(), tt, true);
  // partition layer: region of each point and the texture blend weights
  TileScratch& scratch = tile_scratch();
  std::vector<std::uint8_t>& region = scratch.region;
  std::array<std::vector<float>, kMaxRegions>& weight = scratch.weight;
  partition_.classify_grid(x0, y0, d, t, t, region, weight);
  tile->sediment.resize(tt * tt);
  for (std::size_t m = 0; m < tt * tt; ++m) {
    tile->sediment[m] = static_cast<std::uint8_t>(regions_[region[m]].sediment);
  }
  // texture layer: each region's ripples and rocky relief, cross-faded at borders
  std::vector<float>& tex = scratch.tex;
  for (std::size_t k = 0; k < regions_.size(); ++k) {
    const auto& layers = regions_[k];
    if (!layers.ripples && !layers.rocky) continue;
    const auto& w = weight[k];
    if (*std::max_element(w.begin(), w.end()) <= 0.0f) continue;
    tex.assign(tt * tt, 0.0f);
    if (layers.ripples) layers.ripples->sample_grid(x0, y0, d, t, t, tex.data(), tt, true);
    if (layers.rocky) layers.rocky->sample_grid(x0, y0, d, t, t, tex.data(), tt, true);
    for (std::size_t m = 0; m < tt * tt; ++m)
      h[m] += w[m] * tex[m];
  }
  // clutter rocks on top
  if (!clutter_.empty()) {
    const auto rocks = clutter_.rocks_near(x0, y0, x0 + (t - 1) * d, y0 + (t - 1) * d);
    clutter_.rasterize(rocks, x0, y0, d, t, t, h.data(), tt);
  }
  return tile;
}

void SeabedModel::copy_region(std::int64_t i0, std::int64_t j0, int ni, int nj, float* elevation,
                              std::uint8_t* sediment) const {
  const int t = options_.tile_size;
  const auto tt = static_cast<std::size_t>(t);
  for (std::int64_t ti = tile_of(i0); ti <= tile_of(i0 + ni - 1); ++ti) {
    for (std::int64_t tj = tile_of(j0); tj <= tile_of(j0 + nj - 1); ++tj) {
      const auto tl = tile(ti, tj);
      const std::int64_t ia = std::max(i0, ti * t);
      const std::int64_t ib = std::min(i0 + ni, ti * t + t);
      const std::int64_t ja = std::max(j0, tj * t);
      const std::int64_t jb = std::min(j0 + nj, tj * t + t);
      for (std::int64_t i = ia; i < ib; ++i) {
        const std::size_t src =
            static_cast<std::size_t>(i - ti * t) * tt + static_cast<std::size_t>(ja - tj * t);
        const std::size_t dst = static_cast<std::size_t>(i - i0) * static_cast<std::size_t>(nj) +
                                static_cast<std::size_t>(ja - j0);
        const auto n = static_cast<std::size_t>(jb - ja);
        if (elevation) std::copy_n(tl->elevation_m.data() + src, n, elevation + dst);
        if (sediment) std::copy_n(tl->sediment.data() + src, n, sediment + dst);
      }
    }
  }
}

double SeabedModel::elevation(double x, double y) const {
  const double u = x / spacing_m_;
  const double v = y / spacing_m_;
  const auto i = static_cast<std::int64_t>(std::floor(u));
  const auto j = static_cast<std::int64_t>(std::floor(v));
  float h[4];
  copy_region(i, j, 2, 2, h, nullptr);
  const double fu = u - static_cast<double>(i);
  const double fv = v - static_cast<double>(j);
  return (1 - fu) * ((1 - fv) * h[0] + fv * h[1]) + fu * ((1 - fv) * h[2] + fv * h[3]);
}

SedimentId SeabedModel::sediment_at(double x, double y) const {
  const auto i = static_cast<std::int64_t>(std::llround(x / spacing_m_));
  const auto j = static_cast<std::int64_t>(std::llround(y / spacing_m_));
  std::uint8_t s = 0;
  copy_region(i, j, 1, 1, nullptr, &s);
  return s;
}

void SeabedModel::prepare(double x0, double y0, double x1, double y1, int threads,
                          const std::function<void(double)>& on_progress, int level) const {
  const double d = spacing_m(level);
  const auto lattice = [&](double v) { return static_cast<std::int64_t>(std::floor(v / d)); };
  const std::int64_t ti0 = tile_of(lattice(x0));
  const std::int64_t ti1 = tile_of(lattice(x1) + 1);
  const std::int64_t tj0 = tile_of(lattice(y0));
  const std::int64_t tj1 = tile_of(lattice(y1) + 1);
  const std::int64_t nj = tj1 - tj0 + 1;
  const std::int64_t count = (ti1 - ti0 + 1) * nj;
  std::atomic<std::int64_t> done{0};
  parallel_for(static_cast<std::size_t>(count), threads, [&](std::size_t item, int worker) {
    const auto k = static_cast<std::int64_t>(item);
    tile(ti0 + k / nj, tj0 + k % nj, level);
    const std::int64_t n_done = ++done;
    if (worker == 0 && on_progress)  // the calling thread reports
      on_progress(static_cast<double>(n_done) / static_cast<double>(count));
  });
}

}  // namespace sonarloop::seabed
