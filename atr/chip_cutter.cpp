#include "atr/chip_cutter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sonarloop::atr {
namespace {

// Smallest chip side accepted, pixels.
constexpr int kMinChipPixels = 4;
// Relative difference under which the stream's bin and the chip's range pixel count as equal.
constexpr double kSameBinTolerance = 1e-6;

}  // namespace

const char* cut_status_name(CutStatus s) {
  switch (s) {
    case CutStatus::kOk:
      return "ok";
    case CutStatus::kNotYet:
      return "not_yet";
    case CutStatus::kGone:
      return "gone";
    case CutStatus::kGap:
      return "gap";
    case CutStatus::kOutside:
      return "outside";
  }
  return "?";
}

ChipSpec highlight_chip_spec(int width, int height) {
  if (width < kMinChipPixels || height < kMinChipPixels) {
    throw std::invalid_argument("chip size " + std::to_string(width) + " x " +
                                std::to_string(height) + " pixels: need at least " +
                                std::to_string(kMinChipPixels) + " a side");
  }
  ChipSpec s;
  s.rows = height;
  s.cols = width;
  s.pixel_along_m = chips::kHighlightChipAlong_m / height;
  s.pixel_range_m = chips::kHighlightChipRange_m / width;
  return s;
}

ChipCutter::ChipCutter(const ChipSpec& spec, int margin_rows, int margin_cols)
    : spec_(spec), margin_rows_(margin_rows), margin_cols_(margin_cols) {
  if (spec.rows < kMinChipPixels || spec.cols < kMinChipPixels || !(spec.pixel_along_m > 0.0) ||
      !(spec.pixel_range_m > 0.0) || margin_rows < 0 || margin_cols < 0) {
    throw std::invalid_argument("chip cutter: bad chip spec or margins");
  }
  context_.height = spec.rows + 2 * margin_rows;
  context_.width = spec.cols + 2 * margin_cols;
  context_.pixels.assign(
      static_cast<std::size_t>(context_.height) * static_cast<std::size_t>(context_.width), 0.0f);
  row_seq_.assign(static_cast<std::size_t>(context_.height), 0);
}

ChipCentre ChipCutter::shifted(const ChipCentre& c, int dr, int dc) const {
  ChipCentre s = c;
  s.along_m += (c.side == 1 ? -dr : dr) * spec_.pixel_along_m;
  s.slant_m += dc * spec_.pixel_range_m;
  return s;
}

void ChipCutter::fill_row(const Waterfall& w, std::uint64_t seq, int side, double first_edge_m,
                          float* row) {
  const std::span<const float> L = w.levels(seq, side);
  const double b = w.bin_size_m();
  const double r0 = w.range_start_m();
  const double pr = spec_.pixel_range_m;
  const int ct = context_.width;
  if (std::abs(b - pr) <= kSameBinTolerance * pr) {
    const auto bin0 = static_cast<std::ptrdiff_t>(std::lround((first_edge_m - r0) / b));
    for (int j = 0; j < ct; ++j)
      row[j] = chips::chip_pixel(L[static_cast<std::size_t>(bin0 + j)], spec_.levels);
    return;
  }
  for (int j = 0; j < ct; ++j) {
    // mean power of the stream bins under [lo, hi), weighted by overlap
    const double lo = first_edge_m + j * pr;
    const double hi = lo + pr;
    const auto k_lo =
        std::max<std::ptrdiff_t>(0, static_cast<std::ptrdiff_t>(std::floor((lo - r0) / b)));
    const auto k_hi = std::min(static_cast<std::ptrdiff_t>(L.size()),
                               static_cast<std::ptrdiff_t>(std::ceil((hi - r0) / b)));
    double power = 0.0, weight = 0.0;
    for (std::ptrdiff_t k = k_lo; k < k_hi; ++k) {
      const double overlap = std::min(hi, r0 + static_cast<double>(k + 1) * b) -
                             std::max(lo, r0 + static_cast<double>(k) * b);
      if (overlap <= 0.0) continue;
      power += overlap * std::pow(10.0, L[static_cast<std::size_t>(k)] / 10.0);
      weight += overlap;
    }
    const double level = power > 0.0 ? 10.0 * std::log10(power / weight) : kNoEchoDb;
    row[j] = chips::chip_pixel(level, spec_.levels);
  }
}

CutStatus ChipCutter::cut(const Waterfall& w, const ChipCentre& c) {
  if (w.empty()) return CutStatus::kNotYet;
  const int rt = context_.height;
  const int ct = context_.width;
  const double pa = spec_.pixel_along_m;
  const double first_pos = c.along_m - 0.5 * (rt - 1) * pa;
  const double last_pos = c.along_m + 0.5 * (rt - 1) * pa;

  // the range window, in the stream's bins
  const double pr = spec_.pixel_range_m;
  double first_edge = c.slant_m - (0.5 * spec_.cols + margin_cols_) * pr;
  const double b = w.bin_size_m();
  const double r0 = w.range_start_m();
  if (std::abs(b - pr) <= kSameBinTolerance * pr) {
    first_edge = r0 + static_cast<double>(std::lround((first_edge - r0) / b)) * b;  // snap
  }
  if (first_edge < r0 - 1e-9 * b || first_edge + ct * pr > r0 + w.bins() * b + 1e-9 * b) {
    return CutStatus::kOutside;
  }

  // the pings that can serve the rows
  // a row beyond the newest ping by more than half a ping spacing may get a nearer ping later
  const PingRecord& newest = w.record(w.newest_seq());
  const double half_spacing =
      w.size() > 1 ? 0.5 * std::abs(newest.along_m - w.record(w.newest_seq() - 1).along_m) : 0.0;
  if (footprint_along_m(newest) + half_spacing < last_pos) return CutStatus::kNotYet;
  if (footprint_along_m(w.record(w.oldest_seq())) - half_spacing > first_pos)
    return CutStatus::kGone;
  if (candidates_seq_.capacity() < static_cast<std::size_t>(w.capacity())) {
    candidates_seq_.reserve(static_cast<std::size_t>(w.capacity()));
    candidates_along_.reserve(static_cast<std::size_t>(w.capacity()));
  }
  candidates_seq_.clear();
  candidates_along_.clear();
  for (std::uint64_t s = w.oldest_seq(); s <= w.newest_seq(); ++s) {
    const double fa = footprint_along_m(w.record(s));
    if (fa >= first_pos - kMaxRowGap_m && fa <= last_pos + kMaxRowGap_m) {
      candidates_seq_.push_back(s);
      candidates_along_.push_back(fa);
    }
  }
  if (candidates_seq_.empty()) return CutStatus::kGap;
  const double span = *std::max_element(candidates_along_.begin(), candidates_along_.end()) -
                      *std::min_element(candidates_along_.begin(), candidates_along_.end());
  const double spacing =
      candidates_seq_.size() > 1 ? span / static_cast<double>(candidates_seq_.size() - 1) : 0.0;

  gap_rows_ = 0;
  max_row_distance_m_ = 0.0;
  for (int k = 0; k < rt; ++k) {
    const double pos = first_pos + k * pa;
    std::size_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < candidates_along_.size(); ++i) {
      const double d = std::abs(candidates_along_[i] - pos);
      if (d < best_d) {
        best_d = d;
        best = i;
      }
    }
    if (best_d > kMaxRowGap_m) return CutStatus::kGap;
    if (spacing > 0.0 && best_d > spacing) ++gap_rows_;
    max_row_distance_m_ = std::max(max_row_distance_m_, best_d);
    // starboard: the last ping in row 0; port: the first
    const int row = c.side == 1 ? rt - 1 - k : k;
    row_seq_[static_cast<std::size_t>(row)] = candidates_seq_[best];
    fill_row(w, candidates_seq_[best], c.side, first_edge,
             context_.pixels.data() + static_cast<std::size_t>(row) * static_cast<std::size_t>(ct));
  }
  return CutStatus::kOk;
}

void copy_window(const Chip& context, int margin_rows, int margin_cols, int dr, int dc, Chip& out) {
  if (std::abs(dr) > margin_rows || std::abs(dc) > margin_cols) {
    throw std::out_of_range("chip window shift (" + std::to_string(dr) + ", " + std::to_string(dc) +
                            ") beyond the margins");
  }
  const int rows = context.height - 2 * margin_rows;
  const int cols = context.width - 2 * margin_cols;
  if (out.width != cols || out.height != rows ||
      out.pixels.size() != static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols)) {
    out.width = cols;
    out.height = rows;
    out.pixels.assign(static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols), 0.0f);
  }
  const int r0 = margin_rows + dr;
  const int c0 = margin_cols + dc;
  for (int r = 0; r < rows; ++r) {
    const float* src = context.pixels.data() +
                       static_cast<std::size_t>(r0 + r) * static_cast<std::size_t>(context.width) +
                       static_cast<std::size_t>(c0);
    std::copy(src, src + cols,
              out.pixels.data() + static_cast<std::size_t>(r) * static_cast<std::size_t>(cols));
  }
}

}  // namespace sonarloop::atr
