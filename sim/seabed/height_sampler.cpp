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

}  // namespace sonarloop::seabed
