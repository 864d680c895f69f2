#include "atr/chip_preprocess.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace sonarloop::atr {
namespace {

// The doubles preprocess_into needs for an n-pixel chip whose longer side is `side`:
// intensities and counts (2n), prefix sums (2 (side + 1)), and the median's copy (n).
std::size_t work_size(std::size_t n, int side) {
  return 3 * n + 2 * (static_cast<std::size_t>(side) + 1);
}

void crop_into(ChipView c, int w, int h, std::vector<float>& out) {
  const int col0 = (c.width - w) / 2;
  const int row0 = (c.height - h) / 2;
  for (int r = 0; r < h; ++r) {
    const auto src = c.pixels.begin() + static_cast<std::ptrdiff_t>(r + row0) * c.width + col0;
    std::copy(src, src + w, out.begin() + static_cast<std::ptrdiff_t>(r) * w);
  }
}

// One pass of a centred box sum of half-width `half` along rows or along columns, in place on
// the values v and their pixel counts cnt (w x h), with prefix sums in pv, pc (>= len + 1).
void box_pass(double* v, double* cnt, int w, int h, int half, bool along_rows, double* pv,
              double* pc) {
  const int lines = along_rows ? h : w;
  const int len = along_rows ? w : h;
  const std::size_t step = along_rows ? 1 : static_cast<std::size_t>(w);
  pv[0] = 0.0;
  pc[0] = 0.0;
  for (int line = 0; line < lines; ++line) {
    const std::size_t base = along_rows ? static_cast<std::size_t>(line) * w : line;
    for (int i = 0; i < len; ++i) {
      pv[i + 1] = pv[i] + v[base + i * step];
      pc[i + 1] = pc[i] + cnt[base + i * step];
    }
    for (int i = 0; i < len; ++i) {
      const int lo = std::max(0, i - half);
      const int hi = std::min(len, i + half + 1);
      v[base + i * step] = pv[hi] - pv[lo];
      cnt[base + i * step] = pc[hi] - pc[lo];
    }
  }
}

// The k x k average of the intensity 10^(L/10), back in levels.
void multilook(std::vector<float>& px, int w, int h, int k, double* work) {
  const std::size_t n = px.size();
  double* intensity = work;
  double* count = work + n;
  double* pv = work + 2 * n;
  double* pc = pv + std::max(w, h) + 1;
  for (std::size_t i = 0; i < n; ++i) {
    intensity[i] = std::pow(10.0, px[i] * kChipDbPerLevel / 10.0);
    count[i] = 1.0;
  }
  box_pass(intensity, count, w, h, k / 2, true, pv, pc);
  box_pass(intensity, count, w, h, k / 2, false, pv, pc);
  // count holds the number of the window's pixels inside the chip
  for (std::size_t i = 0; i < n; ++i)
    px[i] = static_cast<float>(10.0 * std::log10(intensity[i] / count[i]) / kChipDbPerLevel);
}

float median_level(const std::vector<float>& px, double* work) {
  std::copy(px.begin(), px.end(), work);
  double* mid = work + px.size() / 2;
  std::nth_element(work, mid, work + px.size());
  return static_cast<float>(*mid);
}

void apply_levels(std::vector<float>& px, ChipLevels levels, double threshold_db, double* work) {
  if (levels == ChipLevels::kDb) return;
  const float med = median_level(px, work);
  const auto t = static_cast<float>(threshold_db / kChipDbPerLevel);
  for (float& p : px) {
    switch (levels) {
      case ChipLevels::kAboveSeabed:
        p = std::max(p - med, 0.0f);
        break;
      case ChipLevels::kBelowSeabed:
        p = std::max(med - p, 0.0f);
        break;
      case ChipLevels::kThreeLevel:
        p = p > med + t ? 1.0f : (p < med - t ? -1.0f : 0.0f);
        break;
      case ChipLevels::kDb:
        break;
    }
  }
}

}  // namespace

const char* chip_levels_name(ChipLevels l) {
  switch (l) {
    case ChipLevels::kDb:
      return "db";
    case ChipLevels::kAboveSeabed:
      return "above_seabed";
    case ChipLevels::kBelowSeabed:
      return "below_seabed";
    case ChipLevels::kThreeLevel:
      return "three_level";
  }
  return "?";
}

void validate_preprocess(const ChipPreprocess& p) {
  if (!(p.crop_fraction > 0.0 && p.crop_fraction <= 1.0)) {
    throw std::invalid_argument("chip pre-processing: crop fraction " +
                                std::to_string(p.crop_fraction) + " is not in (0, 1]");
  }
  if (p.multilook_px < 1 || p.multilook_px % 2 == 0 || p.multilook_px > 63) {
    throw std::invalid_argument("chip pre-processing: multilook window " +
                                std::to_string(p.multilook_px) + " is not an odd size 1..63");
  }
  if (static_cast<int>(p.levels) > static_cast<int>(ChipLevels::kThreeLevel)) {
    throw std::invalid_argument("chip pre-processing: unknown levels mode " +
                                std::to_string(static_cast<int>(p.levels)));
  }
  if (p.levels == ChipLevels::kThreeLevel && !(p.threshold_db > 0.0 && p.threshold_db < 60.0)) {
    throw std::invalid_argument("chip pre-processing: three-level threshold " +
                                std::to_string(p.threshold_db) + " dB is not in (0, 60)");
  }
}

std::string preprocess_label(const ChipPreprocess& p) {
  if (p.is_identity()) return "eq. 9 only";
  std::string s;
  char buf[64];
  const auto add = [&](const char* text) { s += (s.empty() ? "" : " + ") + std::string(text); };
  if (p.crop_fraction != 1.0) {
    std::snprintf(buf, sizeof buf, "crop %.2g", p.crop_fraction);
    add(buf);
  }
  if (p.multilook_px != 1) {
    std::snprintf(buf, sizeof buf, "multilook %d", p.multilook_px);
    add(buf);
  }
  if (p.levels == ChipLevels::kThreeLevel) {
    std::snprintf(buf, sizeof buf, "three_level %g dB", p.threshold_db);
    add(buf);
  } else if (p.levels != ChipLevels::kDb) {
    add(chip_levels_name(p.levels));
  }
  return s;
}

double adaptive_crop_fraction(double chip_side_m, double pixel_m) {
  const double side = std::max(kMinCroppedSide_m, kMinCroppedPixels * pixel_m);
  return std::min(1.0, side / chip_side_m);
}

int cropped_size(int size, double crop_fraction) {
  return std::max(1, static_cast<int>(std::lround(crop_fraction * size)));
}

void PreprocessScratch::reserve(int width, int height) {
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  out.reserve(n);
  level_work.reserve(work_size(n, std::max(width, height)));
}

ChipView preprocess_into(ChipView chip, const ChipPreprocess& p, PreprocessScratch& s) {
  const int w = cropped_size(chip.width, p.crop_fraction);
  const int h = cropped_size(chip.height, p.crop_fraction);
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  s.out.resize(n);  // within the reserved capacity: no allocation
  s.level_work.resize(work_size(n, std::max(w, h)));
  crop_into(chip, w, h, s.out);
  if (p.multilook_px > 1) multilook(s.out, w, h, p.multilook_px, s.level_work.data());
  apply_levels(s.out, p.levels, p.threshold_db, s.level_work.data());
  return ChipView{w, h, s.out};
}

Chip preprocess_chip(ChipView chip, const ChipPreprocess& p) {
  PreprocessScratch s;
  const ChipView v = preprocess_into(chip, p, s);
  return Chip{v.width, v.height, std::move(s.out)};
}

}  // namespace sonarloop::atr
