#include "atr/chip_deripple.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <unsupported/Eigen/FFT>
#include <vector>

namespace sonarloop::atr {
namespace {

using Complex = std::complex<double>;

// The 2-D DFT of an h x w row-major array, in place: rows, then columns (Eigen's FFT module,
// kissfft, any length). inverse divides by w * h.
void dft_2d(std::vector<Complex>& a, int w, int h, bool inverse) {
  // one per thread: it keeps its plans (twiddle factors) per length between calls
  thread_local Eigen::FFT<double> fft;
  std::vector<Complex> in, out;
  auto pass = [&](int lines, int len, std::size_t line_step, std::size_t step) {
    in.resize(static_cast<std::size_t>(len));
    for (int l = 0; l < lines; ++l) {
      const std::size_t base = static_cast<std::size_t>(l) * line_step;
      for (int i = 0; i < len; ++i)
        in[static_cast<std::size_t>(i)] = a[base + static_cast<std::size_t>(i) * step];
      if (inverse) {
        fft.inv(out, in);  // Eigen scales the inverse by 1 / len
      } else {
        fft.fwd(out, in);
      }
      for (int i = 0; i < len; ++i)
        a[base + static_cast<std::size_t>(i) * step] = out[static_cast<std::size_t>(i)];
    }
  };
  pass(h, w, static_cast<std::size_t>(w), 1);  // along each row
  pass(w, h, 1, static_cast<std::size_t>(w));  // along each column
}

// Signed frequency of bin k of an n-point DFT: 0 .. n/2, then -(n - k).
int signed_bin(int k, int n) {
  return k <= n / 2 ? k : k - n;
}

// Inside the low frequencies that deripple never touches (in bins of each axis).
bool in_low_frequencies(int fy, int fx, double min_radius_bins) {
  return static_cast<double>(fy) * fy + static_cast<double>(fx) * fx <
         min_radius_bins * min_radius_bins;
}

int wrap(int k, int n) {
  return ((k % n) + n) % n;
}

struct Spectrum {
  int w = 0, h = 0;
  std::vector<Complex> x;
  std::vector<double> power;
  double at(int ky, int kx) const {
    return power[static_cast<std::size_t>(wrap(ky, h)) * w + wrap(kx, w)];
  }
  // |f| in cycles per pixel
  double radius(int ky, int kx) const {
    const double fy = static_cast<double>(ky) / h, fx = static_cast<double>(kx) / w;
    return std::sqrt(fy * fy + fx * fx);
  }
};

// The median power of each ring: ring b holds the bins outside the low frequencies whose
// |f| rounds to b, b - 1 or b + 1 ring widths (one bin, 1 / max(w, h) cycles per pixel).
struct Rings {
  double width = 0.0;
  std::vector<double> median;
  std::size_t index(double r) const { return static_cast<std::size_t>(std::lround(r / width)); }
};

Rings ring_medians(const Spectrum& s, double min_radius_bins) {
  Rings rings;
  rings.width = 1.0 / std::max(s.w, s.h);
  std::vector<std::vector<double>> by_ring(rings.index(s.radius(s.h / 2, s.w / 2)) + 2);
  for (int ky = 0; ky < s.h; ++ky) {
    for (int kx = 0; kx < s.w; ++kx) {
      const int fy = signed_bin(ky, s.h), fx = signed_bin(kx, s.w);
      if (in_low_frequencies(fy, fx, min_radius_bins)) continue;
      by_ring[rings.index(s.radius(fy, fx))].push_back(s.at(fy, fx));
    }
  }
  rings.median.assign(by_ring.size(), 0.0);
  std::vector<double> tmp;
  for (std::size_t b = 0; b < by_ring.size(); ++b) {
    tmp.clear();
    for (std::size_t n = (b == 0 ? 0 : b - 1); n <= b + 1 && n < by_ring.size(); ++n)
      tmp.insert(tmp.end(), by_ring[n].begin(), by_ring[n].end());
    if (tmp.empty()) continue;
    auto mid = tmp.begin() + static_cast<std::ptrdiff_t>(tmp.size() / 2);
    std::nth_element(tmp.begin(), mid, tmp.end());
    rings.median[b] = *mid;
  }
  return rings;
}

bool strict_local_max(const Spectrum& s, int fy, int fx) {
  const double p = s.at(fy, fx);
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if ((dy != 0 || dx != 0) && s.at(fy + dy, fx + dx) >= p) return false;
    }
  }
  return true;
}

// Scales every bin of the block of half-width `half` around (fy, fx) whose power is above
// `floor` down to it (and records its new power, so that a bin in two overlapping blocks is
// scaled once, to the lower floor).
void notch(Spectrum& s, int fy, int fx, int half, double floor) {
  for (int dy = -half; dy <= half; ++dy) {
    for (int dx = -half; dx <= half; ++dx) {
      const std::size_t i = static_cast<std::size_t>(wrap(fy + dy, s.h)) * s.w + wrap(fx + dx, s.w);
      if (s.power[i] > floor && s.power[i] > 0.0) {
        s.x[i] *= std::sqrt(floor / s.power[i]);
        s.power[i] = floor;
      }
    }
  }
}

}  // namespace

void validate_deripple(const DerippleOptions& o) {
  if (o.max_peaks < 1 || o.max_peaks > 64) {
    throw std::invalid_argument("deripple: max_peaks " + std::to_string(o.max_peaks) +
                                " (allowed 1 to 64)");
  }
  if (!(o.min_peak_ratio >= 1.0) || !std::isfinite(o.min_peak_ratio)) {
    throw std::invalid_argument("deripple: min_peak_ratio must be finite and >= 1");
  }
  if (o.notch_half_width_bins < 0 || o.notch_half_width_bins > 8) {
    throw std::invalid_argument("deripple: notch_half_width_bins " +
                                std::to_string(o.notch_half_width_bins) + " (allowed 0 to 8)");
  }
  if (!(o.min_radius_bins >= 1.0) || !std::isfinite(o.min_radius_bins)) {
    throw std::invalid_argument("deripple: min_radius_bins must be finite and >= 1");
  }
}

Chip deripple_chip(ChipView chip, const DerippleOptions& o, DerippleReport* report) {
  validate_deripple(o);
  if (chip.width <= 0 || chip.height <= 0 ||
      chip.pixels.size() != static_cast<std::size_t>(chip.width) * chip.height) {
    throw std::invalid_argument("deripple: empty chip, or pixels do not match its size");
  }
  if (report) report->peaks.clear();
  Chip out{chip.width, chip.height, {chip.pixels.begin(), chip.pixels.end()}};
  if (chip.width < 4 || chip.height < 4) return out;  // no room for a period and its ring

  double mean = 0.0;
  for (float p : chip.pixels)
    mean += p;
  mean /= static_cast<double>(chip.pixels.size());

  Spectrum s;
  s.w = chip.width;
  s.h = chip.height;
  s.x.resize(chip.pixels.size());
  for (std::size_t i = 0; i < chip.pixels.size(); ++i)
    s.x[i] = Complex(chip.pixels[i] - mean, 0.0);
  dft_2d(s.x, s.w, s.h, false);
  s.power.resize(s.x.size());
  for (std::size_t i = 0; i < s.x.size(); ++i)
    s.power[i] = std::norm(s.x[i]);

  // candidates: one of each mirror pair (the half plane fy > 0, or fy == 0 and fx > 0)
  struct Candidate {
    int fy, fx;
    double ratio, floor;
  };
  std::vector<Candidate> found;
  const Rings rings = ring_medians(s, o.min_radius_bins);
  for (int ky = 0; ky < s.h; ++ky) {
    for (int kx = 0; kx < s.w; ++kx) {
      const int fy = signed_bin(ky, s.h), fx = signed_bin(kx, s.w);
      if (fy < 0 || (fy == 0 && fx <= 0)) continue;
      if (in_low_frequencies(fy, fx, o.min_radius_bins)) continue;
      const double floor = rings.median[rings.index(s.radius(fy, fx))];
      const double power = s.power[static_cast<std::size_t>(ky) * s.w + kx];
      if (floor <= 0.0 || power < o.min_peak_ratio * floor) continue;
      if (strict_local_max(s, fy, fx)) found.push_back({fy, fx, power / floor, floor});
    }
  }
  if (found.empty()) return out;
  std::sort(found.begin(), found.end(), [](const Candidate& a, const Candidate& b) {
    return a.ratio != b.ratio ? a.ratio > b.ratio : (a.fy != b.fy ? a.fy < b.fy : a.fx < b.fx);
  });
  if (found.size() > static_cast<std::size_t>(o.max_peaks)) found.resize(o.max_peaks);
  for (const Candidate& c : found) {
    notch(s, c.fy, c.fx, o.notch_half_width_bins, c.floor);
    notch(s, -c.fy, -c.fx, o.notch_half_width_bins, c.floor);
    if (report) report->peaks.push_back({c.fy, c.fx, c.ratio});
  }

  dft_2d(s.x, s.w, s.h, true);
  for (std::size_t i = 0; i < out.pixels.size(); ++i)
    out.pixels[i] = static_cast<float>(s.x[i].real() + mean);
  return out;
}

}  // namespace sonarloop::atr
