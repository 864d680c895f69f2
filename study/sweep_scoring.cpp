// The resolution study's scoring (study/sweep.h): error rates with Wilson intervals, each test
// chip's classification counted per condition, class, aspect bin and seabed, and the CSV rows.
// The experiments themselves are defined in sweep.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "study/sweep.h"

namespace sonarloop::study {

// the classifier this study code trains and scores (atr/)
using namespace sonarloop::atr;
using targets::TargetType;

ErrorRate error_rate(std::size_t errors, std::size_t n, double z) {
  ErrorRate r;
  r.n = n;
  r.errors = errors;
  r.rate = n ? static_cast<double>(errors) / static_cast<double>(n) : 0.0;
  r.ci = wilson_interval(errors, n, z);
  return r;
}

namespace {

std::string format_number(double v) {
  if (!std::isfinite(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string format_pct(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", 100.0 * v);
  return buf;
}

std::vector<std::string> class_keys(const std::vector<TargetType>& classes) {
  std::vector<std::string> out;
  for (TargetType t : classes)
    out.emplace_back(targets::target_type_info(t).key);
  return out;
}

// The model's classes, and "unknown" when it rejects (open set).
std::vector<std::string> predicted_names(const Model& m, bool open_set) {
  std::vector<std::string> out;
  for (const auto& c : m.classes)
    out.push_back(c.name);
  if (open_set) out.emplace_back("unknown");
  return out;
}

}  // namespace

ConditionResult::ConditionResult(std::size_t index, const SweepExperiment& e, const Model& m)
    : condition(index),
      confusion(class_keys(e.classes),
                predicted_names(m, e.conditions.at(index).reject_quantile > 0.0)) {
  const auto cells = e.classes.size() * static_cast<std::size_t>(std::max(e.aspect_bins, 0));
  aspect_n.assign(cells, 0);
  aspect_errors.assign(cells, 0);
  seabed_n.assign(e.seabed_names.size(), 0);
  seabed_errors.assign(e.seabed_names.size(), 0);
  class_seabed_n.assign(e.classes.size() * e.seabed_names.size(), 0);
  class_seabed_errors.assign(e.classes.size() * e.seabed_names.size(), 0);
}

void score_chip(ConditionResult& out, const SweepExperiment& e, const Model& m, std::size_t truth,
                double aspect_deg, int seabed, const Classification& r) {
  const SweepCondition& c = e.conditions.at(out.condition);
  if (c.held_out >= 0 && truth == static_cast<std::size_t>(c.held_out)) {
    ++out.unknown_n;
    out.unknown_accepted += !r.unknown;
    return;
  }
  if (truth >= e.novel_from) return;  // a novel type another condition tests
  const bool open_set = c.reject_quantile > 0.0;
  if (open_set) {
    ++out.known_n;
    out.known_rejected += r.unknown;
  }
  const bool unknown = open_set && r.unknown;
  const auto predicted = unknown ? m.classes.size() : static_cast<std::size_t>(r.class_index);
  out.confusion.add(truth, predicted);
  const TargetType t = e.classes.at(truth);
  const bool wrong = unknown || m.classes.at(predicted).name != targets::target_type_info(t).key;
  if (e.mine_groups) {
    ++out.mine_n;
    out.mine_errors += r.mine_like != targets::target_type_info(t).mine_like;
  }
  if (e.aspect_bins > 0) {
    const auto cell = truth * static_cast<std::size_t>(e.aspect_bins) +
                      static_cast<std::size_t>(aspect_sector(aspect_deg, e.aspect_bins));
    ++out.aspect_n[cell];
    out.aspect_errors[cell] += wrong;
  }
  if (seabed >= 0 && static_cast<std::size_t>(seabed) < out.seabed_n.size()) {
    ++out.seabed_n[static_cast<std::size_t>(seabed)];
    out.seabed_errors[static_cast<std::size_t>(seabed)] += wrong;
    const std::size_t cell = truth * out.seabed_n.size() + static_cast<std::size_t>(seabed);
    ++out.class_seabed_n[cell];
    out.class_seabed_errors[cell] += wrong;
  }
}

namespace {

// Correct identifications of truth class `t` (the prediction of the same name).
std::size_t correct_of(const ConfusionMatrix& cm, std::size_t t) {
  const auto& pred = cm.predicted_classes();
  const auto it = std::find(pred.begin(), pred.end(), cm.truth_classes()[t]);
  return it == pred.end() ? 0 : cm.count(t, static_cast<std::size_t>(it - pred.begin()));
}

std::string csv_row(const SweepExperiment& e, const SweepCondition& c, const ConditionResult& r,
                    const std::string& x_name, double x, const std::string& cls,
                    const ErrorRate& er) {
  std::string s = e.name + "," + c.series + "," + x_name + "," + format_number(x) + "," +
                  format_number(c.resolution_m * 100.0) + "," + cls + "," + std::to_string(er.n) +
                  "," + std::to_string(er.errors) + "," + format_pct(er.rate) + "," +
                  format_pct(er.ci.lo) + "," + format_pct(er.ci.hi) + "," +
                  std::to_string(c.train_count) + "," + std::to_string(c.p) + "," +
                  std::to_string(c.aspect_sectors) + "," +
                  format_number(1e3 * r.render_s_per_chip) + "," + format_number(r.train_s) + "," +
                  format_number(1e3 * r.classify_s_per_chip) + "," + (r.complete ? "1" : "0");
  return s + "\n";
}

}  // namespace

std::string results_csv(const SweepExperiment& e, const std::vector<ConditionResult>& results) {
  std::string out =
      "experiment,series,x_name,x,resolution_cm,class,n,errors,error_pct,ci_low_pct,ci_high_pct,"
      "train_per_class,p,aspect_sectors,render_ms_per_chip,train_s,classify_ms_per_chip,"
      "complete\n";
  for (const ConditionResult& r : results) {
    const SweepCondition& c = e.conditions.at(r.condition);
    const ConfusionMatrix& cm = r.confusion;
    for (std::size_t t = 0; t < e.classes.size(); ++t) {
      const std::size_t n = cm.row_total(t);
      out += csv_row(e, c, r, c.x_name, c.x, cm.truth_classes()[t],
                     error_rate(n - correct_of(cm, t), n));
    }
    out +=
        csv_row(e, c, r, c.x_name, c.x, "all", error_rate(cm.total() - cm.correct(), cm.total()));
    if (e.mine_groups) {
      out +=
          csv_row(e, c, r, c.x_name, c.x, "mine_vs_non_mine", error_rate(r.mine_errors, r.mine_n));
    }
    if (c.reject_quantile > 0.0) {
      out +=
          csv_row(e, c, r, c.x_name, c.x, "false_reject", error_rate(r.known_rejected, r.known_n));
    }
    if (c.held_out >= 0) {
      out += csv_row(e, c, r, c.x_name, c.x, "unknown_accepted",
                     error_rate(r.unknown_accepted, r.unknown_n));
    }
    if (r.seabed_n.size() > 1) {
      for (std::size_t b = 0; b < r.seabed_n.size(); ++b) {
        out += csv_row(e, c, r, c.x_name, c.x, "seabed_" + e.seabed_names[b],
                       error_rate(r.seabed_errors[b], r.seabed_n[b]));
      }
    }
    if (e.aspect_bins > 0) {
      const auto bins = static_cast<std::size_t>(e.aspect_bins);
      const double width = 360.0 / e.aspect_bins;
      for (std::size_t b = 0; b < bins; ++b) {
        std::size_t n_all = 0, err_all = 0;
        for (std::size_t t = 0; t < e.classes.size(); ++t) {
          const std::size_t k = t * bins + b;
          n_all += r.aspect_n[k];
          err_all += r.aspect_errors[k];
          out += csv_row(e, c, r, "aspect_deg", (static_cast<double>(b) + 0.5) * width,
                         cm.truth_classes()[t], error_rate(r.aspect_errors[k], r.aspect_n[k]));
        }
        out += csv_row(e, c, r, "aspect_deg", (static_cast<double>(b) + 0.5) * width, "all",
                       error_rate(err_all, n_all));
      }
    }
  }
  return out;
}

std::string confusion_csv(const SweepExperiment& e, const std::vector<ConditionResult>& results) {
  std::string out = "experiment,series,x_name,x,truth,predicted,count\n";
  for (const ConditionResult& r : results) {
    const SweepCondition& c = e.conditions.at(r.condition);
    const ConfusionMatrix& cm = r.confusion;
    for (std::size_t t = 0; t < cm.truth_classes().size(); ++t) {
      for (std::size_t p = 0; p < cm.predicted_classes().size(); ++p) {
        out += e.name + "," + c.series + "," + c.x_name + "," + format_number(c.x) + "," +
               cm.truth_classes()[t] + "," + cm.predicted_classes()[p] + "," +
               std::to_string(cm.count(t, p)) + "\n";
      }
    }
  }
  return out;
}

std::string seabed_csv(const SweepExperiment& e, const std::vector<ConditionResult>& results) {
  std::string out =
      "experiment,series,x_name,x,resolution_cm,class,seabed,n,errors,error_pct,ci_low_pct,"
      "ci_high_pct\n";
  if (e.seabed_names.size() < 2) return out;
  const std::size_t seabeds = e.seabed_names.size();
  for (const ConditionResult& r : results) {
    const SweepCondition& c = e.conditions.at(r.condition);
    for (std::size_t t = 0; t < e.classes.size(); ++t) {
      for (std::size_t b = 0; b < seabeds; ++b) {
        const ErrorRate er =
            error_rate(r.class_seabed_errors[t * seabeds + b], r.class_seabed_n[t * seabeds + b]);
        out += e.name + "," + c.series + "," + c.x_name + "," + format_number(c.x) + "," +
               format_number(c.resolution_m * 100.0) + "," +
               std::string(targets::target_type_info(e.classes[t]).key) + "," + e.seabed_names[b] +
               "," + std::to_string(er.n) + "," + std::to_string(er.errors) + "," +
               format_pct(er.rate) + "," + format_pct(er.ci.lo) + "," + format_pct(er.ci.hi) + "\n";
      }
    }
  }
  return out;
}

}  // namespace sonarloop::study
