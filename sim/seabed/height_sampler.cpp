#include "sim/seabed/height_sampler.h"

namespace sonarloop::seabed {

void HeightSampler::bind(const SeabedModel& model, int level) {
  if (model_ == &model && model_uid_ == model.uid() && level_ == level) return;
  model_ = &model;
  model_uid_ = model.uid();
  level_ = level;
  d_ = model.spacing_m(level);
  inv_d_ = 1.0 / d_;
  t_ = model.tile_size();
  last_ = static_cast<std::uint64_t>(t_ - 1);
  h_ = nullptr;
  s_ = nullptr;
  // an impossible current tile, so that the first read takes the slow path
  i0_ = std::numeric_limits<std::int64_t>::min() / 2;
  j0_ = i0_;
  for (auto& s : slots_)
    s = Slot{};
}

const HeightTile& HeightSampler::lookup(std::int64_t ti, std::int64_t tj) {
  const auto key = static_cast<std::uint64_t>(ti) * 0x9E3779B97F4A7C15ULL ^
                   static_cast<std::uint64_t>(tj) * 0xC2B2AE3D27D4EB4FULL;
  Slot& s = slots_[(key >> 58) % kSlots];
  if (!s.tile || s.ti != ti || s.tj != tj) {
    s.tile = model_->tile(ti, tj, level_);
    s.ti = ti;
    s.tj = tj;
  }
  return *s.tile;
}

const HeightTile& HeightSampler::tile_at(std::int64_t i, std::int64_t j) {
  return lookup(model_->tile_of(i), model_->tile_of(j));
}

float HeightSampler::height_at(std::int64_t i, std::int64_t j) {
  const HeightTile& t = tile_at(i, j);
  return t.elevation_m[static_cast<std::size_t>((i - t.ti * t_) * t_ + (j - t.tj * t_))];
}

std::uint8_t HeightSampler::sediment_at(std::int64_t i, std::int64_t j) {
  const HeightTile& t = tile_at(i, j);
  return t.sediment[static_cast<std::size_t>((i - t.ti * t_) * t_ + (j - t.tj * t_))];
}

void HeightSampler::sample_slow(double u, double v, std::int64_t i, std::int64_t j,
                                HeightSample& out) {
  // make the tile holding (i, j) the current one
  const HeightTile& t = tile_at(i, j);
  i0_ = t.ti * t_;
  j0_ = t.tj * t_;
  h_ = t.elevation_m.data();
  s_ = t.sediment.data();
  const std::int64_t a = i - i0_;
  const std::int64_t b = j - j0_;
  const double fu = u - static_cast<double>(i);
  const double fv = v - static_cast<double>(j);
  if (static_cast<std::uint64_t>(a) < last_ && static_cast<std::uint64_t>(b) < last_) {
    sample_in_tile(a, b, fu, fv, out);
    return;
  }
  // a cell on the tile's last row or column: corners from the neighbouring tiles
  const float h00 = height_at(i, j);
  const float h01 = height_at(i, j + 1);
  const float h10 = height_at(i + 1, j);
  const float h11 = height_at(i + 1, j + 1);
  finish(h00, h01, h10, h11, fu, fv, out);
  out.sediment = sediment_at(i + (fu >= 0.5), j + (fv >= 0.5));
}

void HeightSampler::cell_corners_slow(std::int64_t i, std::int64_t j, float h[4],
                                      std::uint8_t sed[4]) {
  // make the tile holding (i, j) the current one
  const HeightTile& t = tile_at(i, j);
  i0_ = t.ti * t_;
  j0_ = t.tj * t_;
  h_ = t.elevation_m.data();
  s_ = t.sediment.data();
  const std::int64_t a = i - i0_;
  const std::int64_t b = j - j0_;
  if (static_cast<std::uint64_t>(a) < last_ && static_cast<std::uint64_t>(b) < last_) {
    const std::int64_t m = a * t_ + b;
    h[0] = h_[m];
    h[1] = h_[m + 1];
    h[2] = h_[m + t_];
    h[3] = h_[m + t_ + 1];
    sed[0] = s_[m];
    sed[1] = s_[m + 1];
    sed[2] = s_[m + t_];
    sed[3] = s_[m + t_ + 1];
    return;
  }
  // a cell on the tile's last row or column: corners from the neighbouring tiles
  const std::int64_t ci[4] = {i, i, i + 1, i + 1};
  const std::int64_t cj[4] = {j, j + 1, j, j + 1};
  for (int c = 0; c < 4; ++c) {
    h[c] = height_at(ci[c], cj[c]);
    sed[c] = sediment_at(ci[c], cj[c]);
  }
}

namespace {

// Advances the fractional position f in cell `index` by d (|d| <= 1); true if the cell changed.
bool step_cell(double& f, std::int64_t& index, double d) {
  f += d;
  if (f >= 1.0) {
    f -= 1.0;
    ++index;
    return true;
  }
  if (f < 0.0) {
    f += 1.0;
    --index;
    return true;
  }
  return false;
}

}  // namespace

void HeightSampler::sample_line(double x0, double y0, double dx, double dy, int n,
                                double* elevation_m, double* dh_dx, double* dh_dy,
                                std::uint8_t* sediment) {
  if (n <= 0) return;
  const double u0 = x0 * inv_d_;
  const double v0 = y0 * inv_d_;
  const double du = dx * inv_d_;
  const double dv = dy * inv_d_;
  std::int64_t i = floor_to_int(u0);
  std::int64_t j = floor_to_int(v0);
  double fu = u0 - static_cast<double>(i);
  double fv = v0 - static_cast<double>(j);
  float h[4];
  std::uint8_t sed[4];
  cell_corners(i, j, h, sed);
  for (int k = 0; k < n; ++k) {
    if (k > 0) {
      // step; |du|, |dv| <= 1, so the line moves at most one cell along each axis
      const bool moved_u = step_cell(fu, i, du);
      const bool moved_v = step_cell(fv, j, dv);
      const bool moved = moved_u || moved_v;
      if (moved) cell_corners(i, j, h, sed);
    }
    const double h00 = h[0], h01 = h[1], h10 = h[2], h11 = h[3];
    const double a0 = h00 + fv * (h01 - h00);  // along v at row i
    const double a1 = h10 + fv * (h11 - h10);  // along v at row i + 1
    elevation_m[k] = a0 + fu * (a1 - a0);
    dh_dx[k] = (a1 - a0) * inv_d_;
    dh_dy[k] = ((h01 - h00) + fu * ((h11 - h10) - (h01 - h00))) * inv_d_;
    sediment[k] = sed[(fu >= 0.5 ? 2 : 0) + (fv >= 0.5 ? 1 : 0)];
  }
}

}  // namespace sonarloop::seabed
