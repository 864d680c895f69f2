#include "products/waterfall.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "drivers/image/png.h"

namespace sonarloop::products {
namespace {

struct Levels {
  double lo_db = 0.0;
  double hi_db = 1.0;
};

// Grey levels from the seabed's own amplitudes: samples beyond each ping's nadir altitude (the
// water column holds only noise), every 7th one, from the 1st to the 99.5th percentile in dB but
// at most kMaxSpanDb wide.
constexpr double kMaxSpanDb = 40.0;

Levels levels_of(const WaterfallData& w) {
  const auto& a = w.amplitude;
  std::vector<float> db;
  db.reserve(a.size() / 7 + 1);
  const auto row = static_cast<std::size_t>(2 * w.bins);
  for (std::size_t k = 0; k < a.size(); k += 7) {
    const std::size_t ping = k / row;
    const int bin = static_cast<int>(k % row) % w.bins;
    const double alt = w.altitude_m[ping];
    if (!(alt > 0.0) || (bin + 0.5) * w.bin_size_m < alt) continue;
    if (a[k] > 0.0f) db.push_back(20.0f * std::log10(a[k]));
  }
  if (db.empty()) return {};
  const auto at = [&](double q) {
    const auto n = static_cast<std::size_t>(q * static_cast<double>(db.size() - 1));
    std::nth_element(db.begin(), db.begin() + static_cast<std::ptrdiff_t>(n), db.end());
    return static_cast<double>(db[n]);
  };
  Levels l{at(0.01), at(0.995)};
  l.lo_db = std::max(l.lo_db, l.hi_db - kMaxSpanDb);
  if (l.hi_db <= l.lo_db) l.hi_db = l.lo_db + 1.0;
  return l;
}

std::uint8_t grey(float amplitude, const Levels& l) {
  if (!(amplitude > 0.0f)) return 0;
  const double v = (20.0 * std::log10(amplitude) - l.lo_db) / (l.hi_db - l.lo_db);
  return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(v, 0.0, 1.0)));
}

// The slant-range image of per-sample values laid out as WaterfallData::amplitude (pings x
// (2 * bins)): the last ping at the top, port mirrored to the left.
template <typename T, typename ToPixel>
void write_slant_png(const std::string& path, const WaterfallData& w, const std::vector<T>& values,
                     ToPixel to_pixel) {
  const int n = w.pings();
  const int width = 2 * w.bins;
  std::vector<std::uint8_t> px(static_cast<std::size_t>(n) * static_cast<std::size_t>(width));
  for (int p = 0; p < n; ++p) {
    const T* row = values.data() + static_cast<std::size_t>(p) * static_cast<std::size_t>(width);
    std::uint8_t* out =
        px.data() + static_cast<std::size_t>(n - 1 - p) * static_cast<std::size_t>(width);
    for (int side = 0; side < 2; ++side) {
      for (int b = 0; b < w.bins; ++b) {
        out[waterfall_column(w.bins, side, b)] = to_pixel(row[side * w.bins + b]);
      }
    }
  }
  image::write_png_gray8(path, width, std::max(n, 1), px);
}

}  // namespace

void write_waterfall_png(const std::string& path, const WaterfallData& w) {
  const Levels l = levels_of(w);
  write_slant_png(path, w, w.amplitude, [&](float a) { return grey(a, l); });
}

void write_label_png(const std::string& path, const WaterfallData& w) {
  if (w.label.size() != w.amplitude.size()) {
    throw std::logic_error("write_label_png: the waterfall was rendered without labels");
  }
  write_slant_png(path, w, w.label, [](std::uint8_t v) { return v; });
}

void write_ground_waterfall_png(const std::string& path, const WaterfallData& w) {
  const int n = w.pings();
  const int width = 2 * w.bins;
  const Levels l = levels_of(w);
  const double dr = w.bin_size_m;
  std::vector<std::uint8_t> px(static_cast<std::size_t>(n) * static_cast<std::size_t>(width), 0);
  for (int p = 0; p < n; ++p) {
    const double a = w.altitude_m[static_cast<std::size_t>(p)];
    if (!(a > 0.0)) continue;
    const float* row =
        w.amplitude.data() + static_cast<std::size_t>(p) * static_cast<std::size_t>(width);
    std::uint8_t* out =
        px.data() + static_cast<std::size_t>(n - 1 - p) * static_cast<std::size_t>(width);
    for (int side = 0; side < 2; ++side) {
      for (int g = 0; g < w.bins; ++g) {
        // ground range at the pixel centre -> slant range -> linear interpolation between bins
        const double x = (g + 0.5) * dr;
        const double r = std::sqrt(x * x + a * a);
        const double u = r / dr - 0.5;
        const int b = static_cast<int>(std::floor(u));
        if (b < 0 || b + 1 >= w.bins) continue;
        const double t = u - b;
        const float v =
            static_cast<float>((1.0 - t) * row[side * w.bins + b] + t * row[side * w.bins + b + 1]);
        out[waterfall_column(w.bins, side, g)] = grey(v, l);
      }
    }
  }
  image::write_png_gray8(path, width, std::max(n, 1), px);
}

}  // namespace sonarloop::products
