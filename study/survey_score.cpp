#include "study/survey_score.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "sim/targets/target_type.h"

namespace sonarloop::study {
namespace {

// A grid over the seabed's extent, one byte per cell: covered or not.
struct CoverGrid {
  double x0 = 0.0, y0 = 0.0, cell = 1.0;
  int nx = 0, ny = 0;
  std::vector<std::uint8_t> covered;

  void mark(double x, double y) {
    const int i = static_cast<int>(std::floor((x - x0) / cell));
    const int j = static_cast<int>(std::floor((y - y0) / cell));
    if (i < 0 || j < 0 || i >= nx || j >= ny) return;
    covered[static_cast<std::size_t>(i) * static_cast<std::size_t>(ny) +
            static_cast<std::size_t>(j)] = 1;
  }
};

// The swath band of one ping: ground ranges [near, far] on both sides, or near > far when none.
struct Band {
  double near_m = 0.0, far_m = -1.0;
};

Band swath_band(const SwathPing& p, double max_range_m, const SurveyScoreOptions& o) {
  Band b;
  const double a = std::isfinite(p.altitude_m) ? std::max(0.0, p.altitude_m) : 0.0;
  if (!std::isfinite(p.altitude_m) || a >= max_range_m) return b;
  b.near_m = o.nadir_gap_m >= 0.0 ? o.nadir_gap_m : a;
  b.far_m = std::sqrt(max_range_m * max_range_m - a * a) - o.far_margin_m;
  return b;
}

}  // namespace

void SurveyScoreOptions::validate() const {
  if (!(match_radius_m > 0.0 && match_radius_m <= 100.0)) {
    throw std::invalid_argument("survey score: match radius must be in (0, 100] m");
  }
  if (!(std::isfinite(nadir_gap_m))) throw std::invalid_argument("survey score: nadir gap");
  if (!(far_margin_m >= 0.0 && std::isfinite(far_margin_m))) {
    throw std::invalid_argument("survey score: far margin must be >= 0 m");
  }
  if (!(along_window_m > 0.0 && along_window_m <= 100.0)) {
    throw std::invalid_argument("survey score: along-track window must be in (0, 100] m");
  }
  if (!(cell_m >= 0.1 && cell_m <= 100.0)) {
    throw std::invalid_argument("survey score: cell must be in [0.1, 100] m");
  }
}

std::vector<StreamObject> stream_objects(std::span<const atr::Contact> contacts) {
  std::vector<StreamObject> out;
  std::map<std::uint64_t, std::size_t> index;  // object id -> out
  std::vector<std::pair<double, double>> sum;  // position sums
  for (const atr::Contact& c : contacts) {
    const std::uint64_t id = c.object != 0 ? c.object : c.id;
    auto [it, added] = index.try_emplace(id, out.size());
    if (added) {
      out.push_back(StreamObject{});
      out.back().id = id;
      sum.emplace_back(0.0, 0.0);
    }
    StreamObject& o = out[it->second];
    auto& s = sum[it->second];
    s.first += c.north_m;
    s.second += c.east_m;
    ++o.looks;
    o.north_m = s.first / o.looks;
    o.east_m = s.second / o.looks;
    // the latest look's decision: fused over the looks when it has one
    if (!c.fused_class.empty()) {
      o.class_name = c.fused_class;
      o.mine_like = c.fused_mine_like;
    } else if (!c.class_name.empty()) {
      o.class_name = c.class_name;
      o.mine_like = c.mine_like;
    }
    if (!c.class_name.empty()) o.unknown = c.unknown;
    o.status = c.status;
  }
  return out;
}

std::string seabed_kind(const scene::Scene& scene, double north_m, double east_m) {
  const auto& regions = scene.desc().seabed.regions;
  if (regions.empty()) return "flat";
  const int r = scene.seabed().region_at(north_m, east_m);
  const scene::TextureDesc& t =
      regions[static_cast<std::size_t>(std::clamp<int>(r, 0, static_cast<int>(regions.size()) - 1))]
          .texture;
  std::string kind;
  const auto add = [&](const char* k) { kind += kind.empty() ? k : std::string("+") + k; };
  if (t.ripples) add("ripples");
  if (t.rocky) add("rocky");
  if (t.clutter && t.clutter->density_per_m2 >= kClutterKindDensity_per_m2) add("clutter");
  return kind.empty() ? "flat" : kind;
}

SurveyScore score_survey(const scene::Scene& scene, std::span<const SwathPing> pings,
                         double max_range_m, std::span<const StreamObject> objects,
                         const SurveyScoreOptions& o) {
  o.validate();
  const scene::SceneDesc& desc = scene.desc();
  SurveyScore s;
  s.objects = static_cast<int>(objects.size());

  // coverage of the targets
  s.targets.resize(desc.targets.size());
  for (std::size_t t = 0; t < desc.targets.size(); ++t) {
    const scene::TargetDesc& td = desc.targets[t];
    const auto& info = targets::target_type_info(td.type);
    TargetOutcome& out = s.targets[t];
    out.name = td.name;
    out.type = std::string(info.key);
    out.mine_like = info.mine_like;
    out.north_m = td.position_m.x();
    out.east_m = td.position_m.y();
    out.seabed = seabed_kind(scene, out.north_m, out.east_m);
  }
  for (const SwathPing& p : pings) {
    const Band b = swath_band(p, max_range_m, o);
    if (b.far_m < b.near_m) continue;
    const double ch = std::cos(p.heading_rad), sh = std::sin(p.heading_rad);
    for (TargetOutcome& t : s.targets) {
      if (t.covered) continue;
      const double dn = t.north_m - p.north_m, de = t.east_m - p.east_m;
      const double along = dn * ch + de * sh;
      const double across = std::fabs(-dn * sh + de * ch);
      t.covered = std::fabs(along) <= o.along_window_m && across >= b.near_m && across <= b.far_m;
    }
  }

  // the covered area, by seabed kind
  CoverGrid g;
  g.x0 = desc.seabed.origin_m.x();
  g.y0 = desc.seabed.origin_m.y();
  g.cell = o.cell_m;
  g.nx = static_cast<int>(std::ceil(desc.seabed.extent_m.x() / o.cell_m));
  g.ny = static_cast<int>(std::ceil(desc.seabed.extent_m.y() / o.cell_m));
  g.covered.assign(static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny), 0);
  const double step = 0.5 * o.cell_m;
  for (const SwathPing& p : pings) {
    const Band b = swath_band(p, max_range_m, o);
    if (b.far_m < b.near_m) continue;
    const double rn = -std::sin(p.heading_rad), re = std::cos(p.heading_rad);  // to starboard
    for (double r = b.near_m; r <= b.far_m; r += step) {
      g.mark(p.north_m + r * rn, p.east_m + r * re);
      g.mark(p.north_m - r * rn, p.east_m - r * re);
    }
  }
  const double cell_km2 = o.cell_m * o.cell_m * 1e-6;
  for (int i = 0; i < g.nx; ++i) {
    for (int j = 0; j < g.ny; ++j) {
      if (!g.covered[static_cast<std::size_t>(i) * static_cast<std::size_t>(g.ny) +
                     static_cast<std::size_t>(j)]) {
        continue;
      }
      const double x = g.x0 + (i + 0.5) * g.cell, y = g.y0 + (j + 0.5) * g.cell;
      s.area_km2 += cell_km2;
      s.area_km2_by_kind[seabed_kind(scene, x, y)] += cell_km2;
    }
  }

  // one-to-one matching, nearest pairs first
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;  // distance, target, object
  for (std::size_t t = 0; t < s.targets.size(); ++t) {
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const double d = std::hypot(objects[i].north_m - s.targets[t].north_m,
                                  objects[i].east_m - s.targets[t].east_m);
      if (d <= o.match_radius_m) pairs.emplace_back(d, t, i);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<char> object_used(objects.size(), 0);
  for (const auto& [d, t, i] : pairs) {
    TargetOutcome& out = s.targets[t];
    if (out.detected || object_used[i]) continue;
    object_used[i] = 1;
    const StreamObject& obj = objects[i];
    out.detected = true;
    out.error_m = d;
    out.looks = obj.looks;
    out.class_name = obj.class_name;
    out.identified = obj.class_name == out.type;
    out.mine_correct = !obj.class_name.empty() && obj.mine_like == out.mine_like;
  }
  const seabed::Clutter& clutter = scene.seabed().clutter();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (object_used[i]) continue;
    const StreamObject& obj = objects[i];
    FalseContact f;
    f.object = obj.id;
    f.north_m = obj.north_m;
    f.east_m = obj.east_m;
    f.seabed = seabed_kind(scene, obj.north_m, obj.east_m);
    f.class_name = obj.class_name;
    f.mine_like = obj.mine_like;
    f.looks = obj.looks;
    if (!clutter.empty()) {
      const double r = o.match_radius_m;
      for (const seabed::Rock& rock :
           clutter.rocks_near(obj.north_m - r, obj.east_m - r, obj.north_m + r, obj.east_m + r)) {
        if (std::hypot(rock.x_m - obj.north_m, rock.y_m - obj.east_m) <= r) {
          f.rock_diameter_m = std::max(f.rock_diameter_m, 2.0 * rock.semi_major_m);
        }
      }
    }
    s.false_contacts.push_back(f);
  }
  return s;
}

std::vector<FrocCounts> froc_counts(const SurveyScore& score,
                                    std::span<const ScoredCandidate> candidates,
                                    std::span<const double> thresholds, double association_radius_m,
                                    double match_radius_m) {
  std::vector<FrocCounts> out;
  struct Obj {
    double n = 0, e = 0, sn = 0, se = 0;
    int looks = 0;
  };
  std::vector<Obj> objects;
  for (const double h : thresholds) {
    objects.clear();
    for (const ScoredCandidate& c : candidates) {
      if (!c.survived || c.score < h) continue;
      Obj* nearest = nullptr;
      double best = association_radius_m;
      for (Obj& o : objects) {
        const double d = std::hypot(o.n - c.north_m, o.e - c.east_m);
        if (d <= best) {
          best = d;
          nearest = &o;
        }
      }
      if (!nearest) {
        objects.push_back(Obj{});
        nearest = &objects.back();
      }
      nearest->sn += c.north_m;
      nearest->se += c.east_m;
      ++nearest->looks;
      nearest->n = nearest->sn / nearest->looks;
      nearest->e = nearest->se / nearest->looks;
    }
    // one-to-one matching, nearest pairs first
    std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
    for (std::size_t t = 0; t < score.targets.size(); ++t) {
      for (std::size_t i = 0; i < objects.size(); ++i) {
        const double d = std::hypot(objects[i].n - score.targets[t].north_m,
                                    objects[i].e - score.targets[t].east_m);
        if (d <= match_radius_m) pairs.emplace_back(d, t, i);
      }
    }
    std::sort(pairs.begin(), pairs.end());
    std::vector<char> target_used(score.targets.size(), 0), object_used(objects.size(), 0);
    FrocCounts f;
    f.threshold = h;
    f.targets = static_cast<int>(score.targets.size());
    f.area_km2 = score.area_km2;
    for (const auto& [d, t, i] : pairs) {
      if (target_used[t] || object_used[i]) continue;
      target_used[t] = object_used[i] = 1;
      f.detected += score.targets[t].covered;
    }
    for (const TargetOutcome& t : score.targets)
      f.covered += t.covered;
    for (const char used : object_used)
      f.false_contacts += !used;
    out.push_back(f);
  }
  return out;
}

void add_froc(std::vector<FrocCounts>& a, std::span<const FrocCounts> b) {
  if (a.empty()) {
    a.assign(b.begin(), b.end());
    return;
  }
  if (a.size() != b.size()) throw std::invalid_argument("add_froc: different thresholds");
  for (std::size_t i = 0; i < a.size(); ++i) {
    a[i].covered += b[i].covered;
    a[i].detected += b[i].detected;
    a[i].false_contacts += b[i].false_contacts;
    a[i].targets += b[i].targets;
    a[i].area_km2 += b[i].area_km2;
  }
}

std::string froc_csv(std::span<const FrocCounts> froc) {
  std::string out =
      "threshold,targets,covered,detected,pd,pd_lo,pd_hi,false_contacts,area_km2,false_per_km2,"
      "false_per_target\n";
  char line[256];
  for (const FrocCounts& f : froc) {
    const atr::Interval ci = atr::wilson_interval(static_cast<std::size_t>(f.detected),
                                                  static_cast<std::size_t>(f.covered));
    std::snprintf(line, sizeof line, "%.4f,%d,%d,%d,%.4f,%.4f,%.4f,%d,%.6f,%.2f,%.4f\n",
                  f.threshold, f.targets, f.covered, f.detected,
                  f.covered ? static_cast<double>(f.detected) / f.covered : 0.0, ci.lo, ci.hi,
                  f.false_contacts, f.area_km2,
                  f.area_km2 > 0 ? f.false_contacts / f.area_km2 : 0.0,
                  f.targets ? static_cast<double>(f.false_contacts) / f.targets : 0.0);
    out += line;
  }
  return out;
}

void SurveyTally::add(const SurveyScore& s) {
  const auto count_target = [](SurveyCounts& c, const TargetOutcome& t) {
    ++c.targets;
    c.covered += t.covered;
    c.detected += t.detected;
    c.identified += t.detected && t.identified;
    c.mine_correct += t.detected && t.mine_correct;
    c.mine_wrong += t.detected && !t.mine_correct;
  };
  for (const TargetOutcome& t : s.targets) {
    count_target(all, t);
    count_target(by_seabed[t.seabed], t);
    count_target(by_type[t.type], t);
  }
  for (const FalseContact& f : s.false_contacts) {
    ++all.false_contacts;
    ++by_seabed[f.seabed].false_contacts;
  }
  all.area_km2 += s.area_km2;
  ++all.surveys;
  for (const auto& [kind, a] : s.area_km2_by_kind)
    by_seabed[kind].area_km2 += a;
}

namespace {

SurveyRow make_row(const std::string& scope, const SurveyCounts& c, bool with_false) {
  SurveyRow r;
  r.scope = scope;
  r.c = c;
  const auto rate = [](int x, int n) { return n > 0 ? static_cast<double>(x) / n : 0.0; };
  const auto ci = [](int x, int n) {
    return atr::wilson_interval(static_cast<std::size_t>(x), static_cast<std::size_t>(n));
  };
  r.pd = rate(c.detected, c.covered);
  r.pd_ci = ci(c.detected, c.covered);
  r.identified = rate(c.identified, c.detected);
  r.identified_ci = ci(c.identified, c.detected);
  r.mine_error = rate(c.mine_wrong, c.detected);
  r.mine_error_ci = ci(c.mine_wrong, c.detected);
  if (with_false) {
    r.false_per_km2 = c.area_km2 > 0.0 ? c.false_contacts / c.area_km2 : 0.0;
    r.false_per_target = c.targets > 0 ? static_cast<double>(c.false_contacts) / c.targets : 0.0;
  }
  return r;
}

}  // namespace

std::vector<SurveyRow> survey_rows(const SurveyTally& t) {
  std::vector<SurveyRow> rows;
  rows.push_back(make_row("all", t.all, true));
  for (const auto& [kind, c] : t.by_seabed)
    rows.push_back(make_row("seabed:" + kind, c, true));
  for (const auto& [type, c] : t.by_type)
    rows.push_back(make_row("type:" + type, c, false));
  return rows;
}

std::string survey_rows_csv(std::span<const SurveyRow> rows) {
  std::string out =
      "scope,surveys,targets,covered,detected,pd,pd_lo,pd_hi,identified,identified_rate,"
      "identified_lo,identified_hi,mine_wrong,mine_error,mine_error_lo,mine_error_hi,"
      "false_contacts,area_km2,false_per_km2,false_per_target\n";
  char line[512];
  for (const SurveyRow& r : rows) {
    std::snprintf(line, sizeof line,
                  "%s,%d,%d,%d,%d,%.4f,%.4f,%.4f,%d,%.4f,%.4f,%.4f,%d,%.4f,%.4f,%.4f,%d,%.6f,"
                  "%.2f,%.4f\n",
                  r.scope.c_str(), r.c.surveys, r.c.targets, r.c.covered, r.c.detected, r.pd,
                  r.pd_ci.lo, r.pd_ci.hi, r.c.identified, r.identified, r.identified_ci.lo,
                  r.identified_ci.hi, r.c.mine_wrong, r.mine_error, r.mine_error_ci.lo,
                  r.mine_error_ci.hi, r.c.false_contacts, r.c.area_km2, r.false_per_km2,
                  r.false_per_target);
    out += line;
  }
  return out;
}

}  // namespace sonarloop::study
