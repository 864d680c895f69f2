// `sonarloop classify`'s scoring and reports (classify_report.h).
#include "study/classify_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "drivers/json/json_writer.h"
#include "study/sweep.h"

namespace sonarloop::study {
namespace {

// The aspect sector of the identified class's nearest subspace; [0, 360) when unknown.
std::pair<double, double> aspect_range(const atr::ClassModel& cls, const atr::Classification& x) {
  if (x.subspace_index < 0) return {0.0, 360.0};
  const atr::Subspace& sub = cls.subspaces[static_cast<std::size_t>(x.subspace_index)];
  return {sub.aspect_min_deg, sub.aspect_max_deg};
}

// Whether a true class is mine-like: the model's flag for a class it knows, else the
// simulator's for a target type, else unknown.
std::optional<bool> truth_mine_like(const atr::Model& m, const std::string& name) {
  if (const int i = m.find_class(name); i >= 0)
    return m.classes[static_cast<std::size_t>(i)].mine_like;
  // the simulator's types and the clutter of training surveys (never mine-like)
  if (name == atr::kClutterClassName) return false;
  const auto sim = target_class_metadata();
  if (const auto it = sim.find(name); it != sim.end()) return it->second.mine_like;
  return std::nullopt;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string number(double v) {
  if (!std::isfinite(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

// ---- scoring ----

ClassifyScores score_chips(const atr::Model& m, const study::ChipFolder& folder,
                           const std::vector<ClassifiedChip>& rows, std::size_t classified,
                           int aspect_bins) {
  ClassifyScores s;
  s.aspect_bins = aspect_bins;
  if (!folder.labelled || !classified) return s;
  const bool mine_decision = m.has_mine_like_class();
  std::vector<std::string> predicted;
  for (const auto& c : m.classes)
    predicted.push_back(c.name);
  s.confusion.emplace(folder.classes, predicted);
  const bool by_aspect = aspect_bins > 0 && folder.aspect_count > 0;
  if (by_aspect) s.bins.resize(static_cast<std::size_t>(aspect_bins));
  for (const ClassifiedChip& r : rows) {
    if (!r.check.ok()) continue;
    const auto truth = static_cast<std::size_t>(
        std::find(folder.classes.begin(), folder.classes.end(), r.chip->label) -
        folder.classes.begin());
    s.confusion->add(truth, static_cast<std::size_t>(r.result.class_index));
    const bool ok = m.classes[static_cast<std::size_t>(r.result.class_index)].name == r.chip->label;
    const auto mine = mine_decision ? truth_mine_like(m, r.chip->label) : std::nullopt;
    if (mine) {
      ++s.mine_total;
      s.mine_correct += r.result.mine_like == *mine;
    }
    if (by_aspect && r.chip->aspect_deg) {
      auto& b =
          s.bins[static_cast<std::size_t>(atr::aspect_sector(*r.chip->aspect_deg, aspect_bins))];
      ++b.total;
      b.correct += ok;
    }
  }
  return s;
}

// ---- console ----

void print_chip_lines(const atr::Model& m, const std::vector<ClassifiedChip>& rows, bool quiet) {
  const bool mine_decision = m.has_mine_like_class();
  for (const ClassifiedChip& r : rows) {
    if (!r.check.ok()) {
      std::fprintf(stderr, "rejected '%s': %s\n", r.chip->source.c_str(), r.check.reason().c_str());
      continue;
    }
    if (quiet) continue;
    const auto& x = r.result;
    const std::string& pred = m.classes[static_cast<std::size_t>(x.class_index)].name;
    std::printf("%-32s %-16s d=%-9.4g", r.chip->source.c_str(), pred.c_str(),
                static_cast<double>(x.distance));
    if (x.runner_up >= 0) {
      std::printf(" next %-12s d=%-9.4g",
                  m.classes[static_cast<std::size_t>(x.runner_up)].name.c_str(),
                  static_cast<double>(x.runner_up_distance));
    }
    if (mine_decision) std::printf(" %-9s", x.mine_like ? "mine" : "non-mine");
    if (x.unknown)
      std::printf(" UNKNOWN (open-set score %.2f)", static_cast<double>(x.open_set_score));
    if (!r.chip->label.empty())
      std::printf(" truth %s%s", r.chip->label.c_str(), r.chip->label == pred ? "" : "  WRONG");
    std::printf("\n");
  }
}

void print_summary(const atr::Model& m, const std::string& model_path, const ClassifyCounts& n) {
  std::printf("classified %zu chip%s (%zu rejected) with %s: %d x %d pixels, %zu classes, p = %d\n",
              n.classified, n.classified == 1 ? "" : "s", n.rejected, model_path.c_str(),
              m.chip_width, m.chip_height, m.classes.size(), m.p);
  if (n.skipped) std::printf("skipped %zu unreadable files (listed on stderr)\n", n.skipped);
  if (n.classified) std::printf("classify time: %.1f us per chip\n", n.per_chip_us);
}

void print_scores(const ClassifyScores& s) {
  if (!s.confusion) return;
  std::printf("\nconfusion matrix (rows: truth, columns: prediction):\n%s",
              s.confusion->to_text().c_str());
  const auto ci = s.confusion->accuracy_interval();
  std::printf("accuracy: %.2f %% (%zu of %zu), 95 %% Wilson interval %.2f-%.2f %%\n",
              100.0 * s.confusion->accuracy(), s.confusion->correct(), s.confusion->total(),
              100.0 * ci.lo, 100.0 * ci.hi);
  if (s.mine_total) {
    const auto mci = atr::wilson_interval(s.mine_correct, s.mine_total);
    std::printf(
        "mine / non-mine: %.2f %% correct (%zu of %zu), 95 %% Wilson interval %.2f-%.2f %%\n",
        100.0 * static_cast<double>(s.mine_correct) / static_cast<double>(s.mine_total),
        s.mine_correct, s.mine_total, 100.0 * mci.lo, 100.0 * mci.hi);
  }
  if (!s.bins.empty()) {
    std::printf("accuracy by true aspect (labels.csv aspect_deg):\n");
    const double w = 360.0 / s.aspect_bins;
    for (std::size_t b = 0; b < s.bins.size(); ++b) {
      if (!s.bins[b].total) continue;
      const auto bi = atr::wilson_interval(s.bins[b].correct, s.bins[b].total);
      std::printf(
          "  %5.1f-%5.1f deg  %6.2f %%  (%zu of %zu, 95 %% %.1f-%.1f %%)\n",
          static_cast<double>(b) * w, static_cast<double>(b + 1) * w,
          100.0 * static_cast<double>(s.bins[b].correct) / static_cast<double>(s.bins[b].total),
          s.bins[b].correct, s.bins[b].total, 100.0 * bi.lo, 100.0 * bi.hi);
    }
  }
}

// ---- files ----

void write_classify_csv(const std::string& path, const atr::Model& m,
                        const std::vector<ClassifiedChip>& rows) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot create '" + path + "'");
  out << "file,truth,status,predicted,distance,runner_up,runner_up_distance,mine_like,"
         "mine_distance,non_mine_distance,aspect_min_deg,aspect_max_deg";
  for (const auto& c : m.classes)
    out << "," << csv_field("distance_" + c.name);
  out << ",reason\n";
  for (const ClassifiedChip& r : rows) {
    out << csv_field(r.chip->source) << "," << csv_field(r.chip->label) << ","
        << atr::chip_status_name(r.check.status);
    if (r.check.ok()) {
      const auto& x = r.result;
      const auto& cls = m.classes[static_cast<std::size_t>(x.class_index)];
      const auto [aspect_min, aspect_max] = aspect_range(cls, x);
      out << "," << csv_field(cls.name) << "," << number(x.distance) << ","
          << (x.runner_up >= 0 ? csv_field(m.classes[static_cast<std::size_t>(x.runner_up)].name)
                               : "")
          << "," << number(x.runner_up_distance) << ",";
      if (m.has_mine_like_class()) {
        out << (x.mine_like ? 1 : 0) << "," << number(x.mine_distance) << ","
            << number(x.non_mine_distance);
      } else {
        out << ",,";
      }
      out << "," << number(aspect_min) << "," << number(aspect_max);
      for (float d : x.class_distance)
        out << "," << number(d);
      out << ",\n";
    } else {
      out << ",,,,,,,,,";
      for (std::size_t i = 0; i < m.classes.size(); ++i)
        out << ",";
      out << "," << csv_field(r.check.reason()) << "\n";
    }
  }
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
}

void write_classify_json(const std::string& path, const atr::Model& m,
                         const std::string& model_path, const study::ChipFolder& folder,
                         const std::vector<ClassifiedChip>& rows, const ClassifyCounts& n,
                         const ClassifyScores& s) {
  const bool mine_decision = m.has_mine_like_class();
  json::Writer w(true);
  w.begin_object().field("model", model_path).field("input", folder.root);
  w.field("chip_width", m.chip_width).field("chip_height", m.chip_height).field("p", m.p);
  w.key("classes").begin_array();
  for (const auto& c : m.classes)
    w.value(c.name);
  w.end_array();
  w.key("chips").begin_array();
  for (const ClassifiedChip& r : rows) {
    w.begin_object().field("file", r.chip->source);
    if (!r.chip->label.empty()) w.field("truth", r.chip->label);
    if (r.chip->aspect_deg) w.field("aspect_deg", *r.chip->aspect_deg);
    w.field("status", atr::chip_status_name(r.check.status));
    if (!r.check.ok()) {
      w.field("reason", r.check.reason()).end_object();
      continue;
    }
    const auto& x = r.result;
    const auto& cls = m.classes[static_cast<std::size_t>(x.class_index)];
    const auto [aspect_min, aspect_max] = aspect_range(cls, x);
    w.field("predicted", cls.name).field("distance", static_cast<double>(x.distance), 7);
    w.key("aspect_range_deg").begin_array().value(aspect_min).value(aspect_max).end_array();
    if (mine_decision) {
      w.field("mine_like", x.mine_like).field("mine_like_by_identity", x.mine_like_by_identity);
      w.field("mine_distance", static_cast<double>(x.mine_distance), 7);
      w.field("non_mine_distance", static_cast<double>(x.non_mine_distance), 7);
    }
    if (std::isfinite(cls.reject_distance)) {
      w.field("unknown", x.unknown)
          .field("open_set_score", static_cast<double>(x.open_set_score), 7);
    }
    w.key("distances").begin_object();
    for (std::size_t i = 0; i < m.classes.size(); ++i) {
      w.field(m.classes[i].name, static_cast<double>(x.class_distance[i]), 7);
    }
    w.end_object().end_object();
  }
  w.end_array();
  w.key("summary").begin_object();
  w.field("classified", static_cast<std::uint64_t>(n.classified));
  w.field("rejected", static_cast<std::uint64_t>(n.rejected));
  w.field("skipped", static_cast<std::uint64_t>(n.skipped));
  w.field("classify_us_per_chip", n.per_chip_us, 4);
  if (s.confusion) {
    const auto ci = s.confusion->accuracy_interval();
    w.field("correct", static_cast<std::uint64_t>(s.confusion->correct()));
    w.field("accuracy", s.confusion->accuracy(), 6);
    w.key("accuracy_ci95").begin_array().value(ci.lo, 6).value(ci.hi, 6).end_array();
    w.key("confusion").begin_object();
    w.key("truth").begin_array();
    for (const auto& t : s.confusion->truth_classes())
      w.value(t);
    w.end_array();
    w.key("predicted").begin_array();
    for (const auto& p : s.confusion->predicted_classes())
      w.value(p);
    w.end_array();
    w.key("counts").begin_array();
    for (std::size_t i = 0; i < s.confusion->truth_classes().size(); ++i) {
      w.begin_array();
      for (std::size_t j = 0; j < s.confusion->predicted_classes().size(); ++j) {
        w.value(static_cast<std::uint64_t>(s.confusion->count(i, j)));
      }
      w.end_array();
    }
    w.end_array().end_object();
    if (s.mine_total) {
      const auto mci = atr::wilson_interval(s.mine_correct, s.mine_total);
      w.key("mine_non_mine").begin_object();
      w.field("correct", static_cast<std::uint64_t>(s.mine_correct));
      w.field("total", static_cast<std::uint64_t>(s.mine_total));
      w.field("accuracy", static_cast<double>(s.mine_correct) / static_cast<double>(s.mine_total),
              6);
      w.key("accuracy_ci95").begin_array().value(mci.lo, 6).value(mci.hi, 6).end_array();
      w.end_object();
    }
    if (!s.bins.empty()) {
      w.key("by_aspect").begin_array();
      const double bw = 360.0 / s.aspect_bins;
      for (std::size_t b = 0; b < s.bins.size(); ++b) {
        w.begin_object();
        w.key("aspect_deg")
            .begin_array()
            .value(static_cast<double>(b) * bw)
            .value(static_cast<double>(b + 1) * bw)
            .end_array();
        w.field("correct", static_cast<std::uint64_t>(s.bins[b].correct));
        w.field("total", static_cast<std::uint64_t>(s.bins[b].total));
        w.end_object();
      }
      w.end_array();
    }
  }
  w.end_object().end_object();
  std::ofstream out(path);
  out << w.str() << '\n';
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
}

}  // namespace sonarloop::study
