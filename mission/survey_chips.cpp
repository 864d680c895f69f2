#include "mission/survey_chips.h"

#include <cmath>
#include <limits>

#include "sim/targets/target_type.h"
#include "units/angles.h"

namespace sonarloop::mission {

std::optional<WaterfallPoint> locate_in_waterfall(const atr::Waterfall& w, double north_m,
                                                  double east_m, double height_m, int side) {
  if (w.empty()) return std::nullopt;
  const atr::PingRecord* best = nullptr;
  double best_along = std::numeric_limits<double>::infinity();
  double best_cross = 0.0;
  for (std::uint64_t s = w.oldest_seq(); s <= w.newest_seq(); ++s) {
    const atr::PingRecord& r = w.record(s);
    if (!std::isfinite(r.altitude_m)) continue;
    const double psi = r.heading_deg * kRadPerDeg;
    const double dn = north_m - r.north_m, de = east_m - r.east_m;
    const double along = dn * std::cos(psi) + de * std::sin(psi);
    const double cross = -dn * std::sin(psi) + de * std::cos(psi);  // + starboard
    if ((cross > 0.0) != (side == 1)) continue;
    // the ping whose footprint passes the point: along offset less the pitch's footprint shift
    const double off = std::fabs(along - (atr::footprint_along_m(r) - r.along_m));
    if (off < best_along) {
      best_along = off;
      best = &r;
      best_cross = cross;
    }
  }
  if (!best) return std::nullopt;
  const double psi = best->heading_deg * kRadPerDeg;
  const double along =
      (north_m - best->north_m) * std::cos(psi) + (east_m - best->east_m) * std::sin(psi);
  const double depth = std::max(0.0, best->altitude_m - 0.5 * height_m);
  return WaterfallPoint{atr::ChipCentre{side, best->along_m + along, std::hypot(best_cross, depth)},
                        best->heading_deg + (side == 1 ? 90.0 : -90.0)};
}

SurveyChipCollector::SurveyChipCollector(const scene::Scene& scene,
                                         const SurveyChipOptions& options, std::uint64_t seed,
                                         std::string source)
    : scene_(scene),
      options_(options),
      cutter_(atr::highlight_chip_spec(options.width, options.height), 0, 0),
      rng_(seed, RngStream::kTraining),
      source_(std::move(source)) {}

bool SurveyChipCollector::cut(const atr::Waterfall& w, const atr::ChipCentre& c,
                              const std::string& label, double aspect_deg, atr::LabelledChip& out) {
  if (cutter_.cut(w, c) != atr::CutStatus::kOk) {
    ++counts_.skipped;
    return false;
  }
  cutter_.window(0, 0, out.chip);
  out.label = label;
  out.aspect_deg = aspect_deg;
  out.source = source_;
  return true;
}

void SurveyChipCollector::on_candidate(const atr::Waterfall& w, const atr::CandidateReport& r) {
  const atr::CandidateFate fate = r.candidate.fate;
  if (fate != atr::CandidateFate::kReported && fate != atr::CandidateFate::kBelowThreshold) return;
  if (r.candidate.detection.score < options_.min_score) return;
  const int side = r.candidate.detection.side;
  const double n = r.contact.north_m, e = r.contact.east_m;
  // a target?
  const scene::TargetDesc* target = nullptr;
  double nearest = options_.target_radius_m;
  for (const scene::TargetDesc& t : scene_.desc().targets) {
    const double d = std::hypot(t.position_m.x() - n, t.position_m.y() - e);
    if (d <= nearest) {
      nearest = d;
      target = &t;
    }
  }
  if (target) {
    const auto& info = targets::target_type_info(target->type);
    const double height = target->size_m.z() > 0.0 ? target->size_m.z() : info.size_m.z();
    const auto p =
        locate_in_waterfall(w, target->position_m.x(), target->position_m.y(), height, side);
    if (!p) {
      ++counts_.skipped;
      return;
    }
    // aspect: the target's heading less the look direction (the dataset's convention)
    const double aspect =
        std::fmod(std::fmod(target->heading_deg - p->look_deg, 360.0) + 360.0, 360.0);
    atr::LabelledChip chip;
    if (cut(w, p->centre, std::string(info.key), aspect, chip)) {
      ++counts_.targets;
      chips_.push_back(std::move(chip));
    }
    return;
  }
  if (!options_.clutter) return;
  // a false alarm: on the rock that made it, if any
  const seabed::Clutter& clutter = scene_.seabed().clutter();
  const seabed::Rock* rock = nullptr;
  std::vector<seabed::Rock> rocks;
  if (!clutter.empty()) {
    const double rr = options_.rock_radius_m;
    rocks = clutter.rocks_near(n - rr, e - rr, n + rr, e + rr);
    for (const seabed::Rock& k : rocks) {
      if (std::hypot(k.x_m - n, k.y_m - e) > rr) continue;
      if (!rock || k.semi_major_m > rock->semi_major_m) rock = &k;
    }
  }
  std::optional<atr::ChipCentre> c;
  if (rock) {
    if (const auto p = locate_in_waterfall(w, rock->x_m, rock->y_m, rock->height_m, side)) {
      c = p->centre;
      ++counts_.rock_centred;
    }
  }
  if (!c) {
    // the detector's centre, as the onboard consumer cuts
    c = atr::ChipCentre{side, r.candidate.detection.along_m, r.candidate.detection.slant_m};
  }
  atr::LabelledChip chip;
  if (!cut(w, *c, options_.clutter_label, 0.0, chip)) return;
  // reservoir sampling (Vitter's algorithm R): each clutter chip cut is kept with probability
  // max_clutter / seen
  ++counts_.clutter_seen;
  const auto cap = static_cast<std::uint64_t>(std::max(0, options_.max_clutter));
  if (clutter_index_.size() < cap) {
    clutter_index_.push_back(chips_.size());
    chips_.push_back(std::move(chip));
    ++counts_.clutter;
    return;
  }
  const auto k =
      static_cast<std::uint64_t>(rng_.uniform() * static_cast<double>(counts_.clutter_seen));
  if (k < cap) chips_[clutter_index_[k]] = std::move(chip);
}

}  // namespace sonarloop::mission
