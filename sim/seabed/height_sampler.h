#pragma once
// Fast reads of one detail level of a SeabedModel for the profile renderer's inner loop: the
// bilinear height, its gradient and the sediment at any point, straight from the heightmap
// tiles, with no lock and no allocation on the common path.
//
// A sampler belongs to one thread. It keeps the tile it last read from, so that consecutive
// reads along a ground line cost a few multiply-adds and four loads; crossing into another tile
// looks it up in a small direct-mapped table of tile pointers, and only a miss there goes to the
// model's (locked) tile cache, generating the tile if nobody has yet. The table holds shared
// pointers, so a tile it holds stays valid even if the model's cache evicts it.
//
// Interpolation is the one Scene::seabed_z uses (bilinear between lattice points; the sediment
// is that of the nearest lattice point), so the profile renderer samples exactly the surface the
// rest of the simulator reports.
#include <array>
#include <cstdint>
#include <limits>
#include <memory>

#include "sim/seabed/seabed_model.h"

namespace sonarloop::seabed {

struct HeightSample {
  double elevation_m = 0.0;  // positive up (frames.h)
  double dh_dx = 0.0;        // gradient of the bilinear surface (north, east), dimensionless
  double dh_dy = 0.0;
  std::uint8_t sediment = 0;  // SedimentId of the nearest lattice point
};

class HeightSampler {
 public:
  // Reads level `level` of `model` from now on. Keeps the cached tiles when the model (by uid)
  // and level are unchanged; drops them otherwise.
  void bind(const SeabedModel& model, int level);
  bool bound() const { return model_ != nullptr; }
  int level() const { return level_; }
  double spacing_m() const { return d_; }

  // The surface at world (x, y) (north, east).
  void sample(double x, double y, HeightSample& out) {
    const double u = x * inv_d_;
    const double v = y * inv_d_;
    const std::int64_t i = floor_to_int(u);
    const std::int64_t j = floor_to_int(v);
    const std::int64_t a = i - i0_;
    const std::int64_t b = j - j0_;
    // fast path: the whole cell inside the current tile
    if (static_cast<std::uint64_t>(a) < last_ && static_cast<std::uint64_t>(b) < last_) {
      sample_in_tile(a, b, u - static_cast<double>(i), v - static_cast<double>(j), out);
      return;
    }
    sample_slow(u, v, i, j, out);
  }

  // The surface at the n points (x0 + k·dx, y0 + k·dy), k = 0 .. n−1, with |dx| and |dy| at
  // most the lattice spacing: the values sample() gives (up to rounding), faster along a line,
  // since a cell's corners are read only when the line enters it.
  void sample_line(double x0, double y0, double dx, double dy, int n, double* elevation_m,
                   double* dh_dx, double* dh_dy, std::uint8_t* sediment);

  // Makes (if needed) and caches the tile holding lattice point (i, j) of the bound level.
  const HeightTile& tile_at(std::int64_t i, std::int64_t j);

 private:
  static std::int64_t floor_to_int(double x) {
    const auto t = static_cast<std::int64_t>(x);  // truncates towards zero
    return t - (static_cast<double>(t) > x);
  }
  void finish(double h00, double h01, double h10, double h11, double fu, double fv,
              HeightSample& out) const {
    // h(u, v) bilinear; h00 = (i, j), h01 = (i, j+1), h10 = (i+1, j), h11 = (i+1, j+1)
    const double a0 = h00 + fv * (h01 - h00);  // along v at row i
    const double a1 = h10 + fv * (h11 - h10);  // along v at row i + 1
    out.elevation_m = a0 + fu * (a1 - a0);
    out.dh_dx = (a1 - a0) * inv_d_;
    out.dh_dy = ((h01 - h00) + fu * ((h11 - h10) - (h01 - h00))) * inv_d_;
  }
  // cell (a, b) of the current tile, fractional position (fu, fv) inside it
  void sample_in_tile(std::int64_t a, std::int64_t b, double fu, double fv, HeightSample& out) {
    const float* h = h_ + a * t_ + b;
    finish(h[0], h[1], h[t_], h[t_ + 1], fu, fv, out);
    out.sediment = s_[(a + (fu >= 0.5)) * t_ + b + (fv >= 0.5)];
  }
  void sample_slow(double u, double v, std::int64_t i, std::int64_t j, HeightSample& out);
  // the four corners (heights and sediments) of cell (i, j): (i, j), (i, j+1), (i+1, j), (i+1, j+1)
  void cell_corners(std::int64_t i, std::int64_t j, float h[4], std::uint8_t sed[4]) {
    const std::int64_t a = i - i0_;
    const std::int64_t b = j - j0_;
    if (static_cast<std::uint64_t>(a) < last_ && static_cast<std::uint64_t>(b) < last_) {
      const float* p = h_ + (a * t_ + b);
      const std::uint8_t* q = s_ + (a * t_ + b);
      h[0] = p[0];
      h[1] = p[1];
      h[2] = p[t_];
      h[3] = p[t_ + 1];
      sed[0] = q[0];
      sed[1] = q[1];
      sed[2] = q[t_];
      sed[3] = q[t_ + 1];
      return;
    }
    cell_corners_slow(i, j, h, sed);
  }
  void cell_corners_slow(std::int64_t i, std::int64_t j, float h[4], std::uint8_t sed[4]);
  float height_at(std::int64_t i, std::int64_t j);
  std::uint8_t sediment_at(std::int64_t i, std::int64_t j);
  const HeightTile& lookup(std::int64_t ti, std::int64_t tj);

  struct Slot {
    std::int64_t ti = 0;
    std::int64_t tj = 0;
    std::shared_ptr<const HeightTile> tile;
  };
  static constexpr std::size_t kSlots = 64;

  const SeabedModel* model_ = nullptr;
  std::uint64_t model_uid_ = 0;
  int level_ = 0;
  double d_ = 1.0;
  double inv_d_ = 1.0;
  std::int64_t t_ = 1;      // tile size T
  std::uint64_t last_ = 0;  // T - 1: cells whose four corners lie in one tile
  // the current tile: its first lattice point and data (null before the first read)
  std::int64_t i0_ = 0;
  std::int64_t j0_ = 0;
  const float* h_ = nullptr;
  const std::uint8_t* s_ = nullptr;
  std::array<Slot, kSlots> slots_{};
};

}  // namespace sonarloop::seabed
