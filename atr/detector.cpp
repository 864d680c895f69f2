#include "atr/detector.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sonarloop::atr {
namespace {

// Fewest bins in a background block: a median of fewer speckled samples is too noisy.
constexpr int kMinBlockBins = 4;

void require(bool ok, const char* what, double value, const char* allowed) {
  if (!ok) {
    throw std::invalid_argument(std::string("detector: ") + what + " = " + std::to_string(value) +
                                " is out of range; allowed: " + allowed);
  }
}

// Median of v (reorders it); v must not be empty.
float median(std::span<float> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

double ground_of(double slant_m, double altitude_m) {
  return std::sqrt(std::max(0.0, slant_m * slant_m - altitude_m * altitude_m));
}

}  // namespace

const char* candidate_fate_name(CandidateFate f) {
  switch (f) {
    case CandidateFate::kReported:
      return "reported";
    case CandidateFate::kSuppressed:
      return "suppressed";
    case CandidateFate::kBelowThreshold:
      return "below_threshold";
    case CandidateFate::kRejected:
      return "rejected";
  }
  return "?";
}

void DetectorOptions::validate() const {
  require(min_ground_m >= 0.0 && min_ground_m < 1000.0, "min_ground_m", min_ground_m, "0..1000");
  require(background_block_m > 0.0 && background_block_m <= 100.0, "background_block_m",
          background_block_m, "(0, 100]");
  require(background_blocks >= 1 && background_blocks <= 101 && background_blocks % 2 == 1,
          "background_blocks", background_blocks, "odd, 1..101");
  require(highlight_above_db >= 0.0, "highlight_above_db", highlight_above_db, ">= 0");
  require(shadow_below_db >= 0.0, "shadow_below_db", shadow_below_db, ">= 0");
  require(shadow_min_m > 0.0, "shadow_min_m", shadow_min_m, "> 0");
  require(highlight_before_m >= 0.0, "highlight_before_m", highlight_before_m, ">= 0");
  require(link_along_m > 0.0, "link_along_m", link_along_m, "> 0");
  require(min_pings >= 1, "min_pings", min_pings, ">= 1");
  require(min_along_m >= 0.0 && max_along_m >= min_along_m, "max_along_m", max_along_m,
          ">= min_along_m >= 0");
  require(min_height_m >= 0.0, "min_height_m", min_height_m, ">= 0");
  require(max_height_m > min_height_m, "max_height_m", max_height_m, "> min_height_m");
  require(candidate_min_height_m >= 0.0 && candidate_min_height_m <= min_height_m,
          "candidate_min_height_m", candidate_min_height_m, "0 .. min_height_m");
  require(min_separation_m >= 0.0, "min_separation_m", min_separation_m, ">= 0");
  require(settle_m >= link_along_m, "settle_m", settle_m, ">= link_along_m");
}

Detector::Detector(const DetectorOptions& options) : options_(options) {
  options_.validate();
  for (auto& o : open_)
    o.reserve(kMaxOpenObjects);
  pending_.reserve(kMaxPendingObjects);
  recent_.reserve(kMaxRecentContacts);
  out_.reserve(kMaxPendingObjects);
  decided_.reserve(2 * kMaxOpenObjects + kMaxPendingObjects);
  hits_.reserve(kMaxRecentHits);
}

void Detector::reset() {
  for (auto& o : open_)
    o.clear();
  pending_.clear();
  recent_.clear();
  recent_next_ = 0;
  out_.clear();
  decided_.clear();
  hits_.clear();
  hits_next_ = 0;
  bins_ = 0;
}

void Detector::configure(const Waterfall& w) {
  reset();
  bins_ = w.bins();
  bin_size_m_ = w.bin_size_m();
  const auto n = static_cast<std::size_t>(bins_);
  block_median_.assign(n, 0.0f);
  block_background_.assign(n, 0.0f);
  scratch_.assign(n, 0.0f);
  background_.assign(n, 0.0f);
}

void Detector::background(std::span<const float> levels, double bin_size_m, int start_bin,
                          std::span<float> out) {
  const int n = static_cast<int>(levels.size());
  if (scratch_.size() < levels.size()) {
    // sized here when called directly (tests); process() sizes them in configure()
    scratch_.resize(levels.size());
    block_median_.resize(levels.size());
    block_background_.resize(levels.size());
  }
  const int nb = std::max(kMinBlockBins,
                          static_cast<int>(std::lround(options_.background_block_m / bin_size_m)));
  start_bin = std::clamp(start_bin, 0, n);
  const int blocks = (n - start_bin) / nb;
  if (blocks < 1) {
    std::fill(out.begin(), out.end(), kNoEchoDb);
    return;
  }
  // 1. the median of every block
  for (int j = 0; j < blocks; ++j) {
    const auto first = levels.begin() + start_bin + j * nb;
    std::copy(first, first + nb, scratch_.begin());
    block_median_[static_cast<std::size_t>(j)] =
        median(std::span<float>(scratch_.data(), static_cast<std::size_t>(nb)));
  }
  // 2. the median of the block medians around each block
  const int half = options_.background_blocks / 2;
  for (int j = 0; j < blocks; ++j) {
    const int lo = std::max(0, j - half);
    const int hi = std::min(blocks - 1, j + half);
    std::copy(block_median_.begin() + lo, block_median_.begin() + hi + 1, scratch_.begin());
    block_background_[static_cast<std::size_t>(j)] =
        median(std::span<float>(scratch_.data(), static_cast<std::size_t>(hi - lo + 1)));
  }
  // 3. per bin (the bins past the last whole block take its value)
  for (int k = 0; k < n; ++k) {
    const int j = k < start_bin ? 0 : std::min((k - start_bin) / nb, blocks - 1);
    out[static_cast<std::size_t>(k)] = block_background_[static_cast<std::size_t>(j)];
  }
}

std::span<const Detection> Detector::process(const Waterfall& w) {
  out_.clear();
  decided_.clear();
  if (w.empty()) return out_;
  if (bins_ != w.bins() || bin_size_m_ != w.bin_size_m()) configure(w);
  ++stats_.pings;
  const std::uint64_t seq = w.newest_seq();
  const PingRecord& r = w.record(seq);
  if (!std::isfinite(r.altitude_m)) {
    ++stats_.pings_no_altitude;
    return out_;
  }
  const double along = footprint_along_m(r);
  for (int side = 0; side < 2; ++side) {
    detect_side(w, seq, side, along);
    close_objects(w, along, side, false);
  }
  decide(along, false);
  return out_;
}

std::span<const Detection> Detector::finish(const Waterfall& w) {
  out_.clear();
  decided_.clear();
  if (w.empty() || bins_ == 0) return out_;
  for (int side = 0; side < 2; ++side)
    close_objects(w, 0.0, side, true);
  decide(0.0, true);
  return out_;
}

void Detector::detect_side(const Waterfall& w, std::uint64_t seq, int side, double along) {
  const std::span<const float> L = w.levels(seq, side);
  const double a = w.record(seq).altitude_m;
  const double b = bin_size_m_;
  const int n = bins_;
  const double start_slant = std::hypot(a, options_.min_ground_m);
  const int start =
      std::clamp(static_cast<int>(std::ceil((start_slant - w.range_start_m()) / b)), 0, n);
  background(L, b, start, background_);
  const auto B = [&](int k) { return background_[static_cast<std::size_t>(k)]; };
  const auto level = [&](int k) { return L[static_cast<std::size_t>(k)]; };
  const auto shadow = [&](int k) { return level(k) <= B(k) - options_.shadow_below_db; };
  const int min_run = std::max(1, static_cast<int>(std::ceil(options_.shadow_min_m / b - 1e-9)));
  const int before = static_cast<int>(std::lround(options_.highlight_before_m / b));

  int k = start;
  while (k < n) {
    if (!shadow(k)) {
      ++k;
      continue;
    }
    // the run, bridging single-bin gaps; it ends on a shadow bin
    int e = k;
    while (e + 1 < n && (shadow(e + 1) || (e + 2 < n && shadow(e + 2))))
      ++e;
    if (e - k + 1 >= min_run) {
      PingHit hit;
      hit.highlight_bin = -1;
      hit.peak_db = -300.0f;
      for (int h = std::max(start, k - before); h <= std::min(k + 1, e); ++h) {
        if (level(h) >= B(h) + options_.highlight_above_db &&
            level(h) >= options_.highlight_min_db) {
          if (hit.highlight_bin < 0) hit.highlight_bin = h;
          if (level(h) > hit.peak_db) {
            hit.peak_db = level(h);
            hit.peak_above_db = level(h) - B(h);
          }
          ++hit.highlight_bins;
          hit.highlight_above_sum_db += level(h) - B(h);
        }
      }
      if (hit.highlight_bin >= 0) {
        hit.shadow_begin = k;
        hit.shadow_end = e;
        for (int j = k; j <= e; ++j)
          hit.shadow_depth_sum_db += B(j) - level(j);
        add_ping_detection(w, seq, side, along, hit);
      }
    }
    k = e + 1;
  }
}

void Detector::add_ping_detection(const Waterfall& w, std::uint64_t seq, int side, double along,
                                  const PingHit& hit) {
  const int highlight_bin = hit.highlight_bin;
  const int shadow_begin = hit.shadow_begin;
  const int shadow_end = hit.shadow_end;
  ++stats_.ping_detections;
  if (hits_.size() < static_cast<std::size_t>(kMaxRecentHits)) {
    hits_.push_back(Hit{along, side});
  } else {
    hits_[hits_next_] = Hit{along, side};
    hits_next_ = (hits_next_ + 1) % hits_.size();
  }
  const PingRecord& r = w.record(seq);
  const double b = bin_size_m_;
  const double r0 = w.range_start_m();
  // this ping's share of the along-track (its spacing to the previous ping)
  double spacing = 0.0;
  if (w.contains(seq - 1) && seq > 0) spacing = std::abs(r.along_m - w.record(seq - 1).along_m);
  const double g0 = ground_of(r0 + shadow_begin * b, r.altitude_m);
  const double g1 = ground_of(r0 + (shadow_end + 1) * b, r.altitude_m);
  const double height = g1 > 0.0 ? (g1 - g0) * r.altitude_m / g1 : 0.0;

  std::vector<Object>& open = open_[side];
  Object* o = nullptr;
  for (Object& c : open) {
    if (std::abs(along - c.last_along) <= options_.link_along_m && highlight_bin <= c.far_bin &&
        shadow_end >= c.near_bin) {
      o = &c;
      break;
    }
  }
  if (!o) {
    if (open.size() == static_cast<std::size_t>(kMaxOpenObjects)) {
      // pool full: close the object seen longest ago
      ++stats_.overflows;
      std::size_t oldest = 0;
      for (std::size_t i = 1; i < open.size(); ++i)
        if (open[i].last_along < open[oldest].last_along) oldest = i;
      retire(w, side, oldest);
    }
    open.push_back(Object{});
    o = &open.back();
    o->side = side;
    o->first_seq = seq;
    o->last_seq = seq;
    o->first_along = along;
    o->last_along = along;
    o->near_bin = highlight_bin;
    o->far_bin = shadow_end;
    o->pings = 1;
  } else if (o->last_seq != seq) {
    ++o->pings;
    o->last_seq = seq;
  }
  o->first_along = std::min(o->first_along, along);
  o->last_along = std::max(o->last_along, along);
  o->near_bin = std::min(o->near_bin, highlight_bin);
  o->far_bin = std::max(o->far_bin, shadow_end);
  o->centre_sum += 0.5 * (highlight_bin + shadow_begin);
  ++o->centre_count;
  o->along_sum += along;
  o->area_m2 += (shadow_end - shadow_begin + 1) * b * spacing;
  if (height > o->height1) {
    o->height2 = o->height1;
    o->height1 = height;
  } else if (height > o->height2) {
    o->height2 = height;
  }
  if (hit.peak_db > o->highlight_db) {
    o->highlight_db = hit.peak_db;
    o->highlight_above_db = hit.peak_above_db;
  }
  o->shadow_depth_sum_db += hit.shadow_depth_sum_db;
  o->shadow_bins += shadow_end - shadow_begin + 1;
  o->highlight_area_m2 += hit.highlight_bins * b * spacing;
  o->highlight_above_sum_db += hit.highlight_above_sum_db;
  o->highlight_bins += hit.highlight_bins;
}

Detection Detector::to_detection(const Waterfall& w, const Object& o) const {
  Detection d;
  d.side = o.side;
  d.first_seq = o.first_seq;
  d.last_seq = o.last_seq;
  d.pings = o.pings;
  d.along_m = 0.5 * (o.first_along + o.last_along);
  d.along_extent_m = o.last_along - o.first_along;
  // the ping whose footprint is nearest the centre
  d.centre_seq = o.first_seq;
  double best = std::numeric_limits<double>::infinity();
  for (std::uint64_t s = o.first_seq; s <= o.last_seq; ++s) {
    if (!w.contains(s)) continue;
    const double dist = std::abs(footprint_along_m(w.record(s)) - d.along_m);
    if (dist < best) {
      best = dist;
      d.centre_seq = s;
    }
  }
  const double b = bin_size_m_;
  const double r0 = w.range_start_m();
  d.slant_m = r0 + (o.centre_sum / std::max(1, o.centre_count) + 0.5) * b;
  const double a = w.contains(d.centre_seq) ? w.record(d.centre_seq).altitude_m : 0.0;
  d.ground_m = ground_of(d.slant_m, a);
  d.near_m = r0 + o.near_bin * b;
  d.far_m = r0 + (o.far_bin + 1) * b;
  d.height_m = o.pings >= 2 ? o.height2 : o.height1;
  d.shadow_area_m2 = o.area_m2;
  d.highlight_db = o.highlight_db;
  d.highlight_above_db = o.highlight_above_db;
  d.shadow_below_db = o.shadow_bins > 0 ? o.shadow_depth_sum_db / o.shadow_bins : 0.0;
  d.highlight_area_m2 = o.highlight_area_m2;
  d.highlight_mean_above_db =
      o.highlight_bins > 0 ? o.highlight_above_sum_db / o.highlight_bins : 0.0;
  int hits = 0;
  for (const Hit& h : hits_)
    hits += h.side == o.side && std::abs(h.along - d.along_m) <= kClutterWindow_m;
  d.clutter_hits_per_m = hits / (2.0 * kClutterWindow_m);
  d.score = d.height_m;
  return d;
}

void Detector::close_objects(const Waterfall& w, double along_now, int side, bool all) {
  std::vector<Object>& open = open_[side];
  for (std::size_t i = 0; i < open.size();) {
    if (all || along_now - open[i].last_along > options_.link_along_m) {
      retire(w, side, i);  // moves the last object to i
    } else {
      ++i;
    }
  }
}

void Detector::retire(const Waterfall& w, int side, std::size_t index) {
  std::vector<Object>& open = open_[side];
  const Object& o = open[index];
  ++stats_.objects;
  Candidate c;
  c.detection = to_detection(w, o);
  const Detection& d = c.detection;
  std::uint8_t failed = 0;
  if (o.pings < options_.min_pings) failed |= kGatePings;
  if (d.along_extent_m < options_.min_along_m) failed |= kGateAlongShort;
  if (d.along_extent_m > options_.max_along_m) failed |= kGateAlongLong;
  if (d.height_m > options_.max_height_m) failed |= kGateTall;
  if (d.score < options_.candidate_min_height_m) failed |= kGateFloor;
  if (failed == 0 && pending_.size() >= static_cast<std::size_t>(kMaxPendingObjects)) {
    ++stats_.overflows;
    failed |= kGateOverflow;
  }
  if (failed != 0) {
    ++stats_.rejected;
    c.failed_gates = failed;
    decided_.push_back(c);
  } else {
    pending_.push_back(d);
  }
  open[index] = open.back();
  open.pop_back();
}

void Detector::decide(double along_now, bool all) {
  auto distance = [](const Detection& a, const Detection& b) {
    if (a.side != b.side) return a.ground_m + b.ground_m;  // across the track
    return std::hypot(a.along_m - b.along_m, a.ground_m - b.ground_m);
  };
  for (std::size_t i = 0; i < pending_.size();) {
    const Detection& p = pending_[i];
    const double last_along = p.along_m + 0.5 * p.along_extent_m;
    if (!all && along_now < last_along + options_.settle_m) {
      ++i;
      continue;
    }
    // suppressed only by a candidate of higher score (decided: at least as high), so that the
    // survivors above any threshold are the contacts of that threshold
    bool suppressed = false;
    for (const Detection& q : recent_)
      suppressed = suppressed || (q.score >= p.score && distance(p, q) < options_.min_separation_m);
    for (std::size_t j = 0; j < pending_.size() && !suppressed; ++j) {
      if (j == i) continue;
      const Detection& q = pending_[j];
      const bool stronger = q.score > p.score || (q.score == p.score && j < i);
      suppressed = stronger && distance(p, q) < options_.min_separation_m;
    }
    Candidate c;
    c.detection = p;
    if (suppressed) {
      ++stats_.suppressed;
      c.fate = CandidateFate::kSuppressed;
    } else {
      if (p.score >= options_.min_height_m) {
        ++stats_.reported;
        c.fate = CandidateFate::kReported;
        out_.push_back(p);
      } else {
        ++stats_.below_threshold;
        c.fate = CandidateFate::kBelowThreshold;
      }
      if (recent_.size() < static_cast<std::size_t>(kMaxRecentContacts)) {
        recent_.push_back(p);
      } else {
        recent_[recent_next_] = p;
        recent_next_ = (recent_next_ + 1) % recent_.size();
      }
    }
    decided_.push_back(c);
    pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(i));
  }
}

}  // namespace sonarloop::atr
